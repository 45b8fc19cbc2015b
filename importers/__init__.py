"""Built-in importers plugins, registered through entry points."""
