"""Built-in device plugins, registered through entry points."""
