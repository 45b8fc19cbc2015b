"""haptic-timeline: design haptic icons on a multitrack timeline (model, edits, mixer, files)."""
