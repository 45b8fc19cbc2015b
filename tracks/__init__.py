"""Built-in track kinds, registered through the haptic_timeline.tracks entry point."""
