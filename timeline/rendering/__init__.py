"""Rendering: a project's layers as arrays (the mixer, one clip at a time), the blocks and
tables a device plays, the source sound, and notes on what a rate cannot carry.
"""
