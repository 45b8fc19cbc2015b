"""The haptic-timeline command line: one module per verb."""
