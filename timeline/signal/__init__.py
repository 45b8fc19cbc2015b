"""Signals: sample arrays, resampling, splines, fades, closed-form generators and their
band-limited synthesis, compiled loops, render quality presets and memory bounds.

The lowest layer above errors: plain numpy, no project, no tile.
"""
