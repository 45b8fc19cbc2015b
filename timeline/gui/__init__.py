"""The editor: a PySide6 view over the Qt-free model; every change goes through timeline.edits."""
