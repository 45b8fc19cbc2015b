"""Tiles: unitless shapes over an axis (seconds or radians) that clips place on tracks.

tile holds the kinds of tile (sampled, spline, generator) and vibration_tile the vibrotactile
design kept as envelopes; templates is the palette's Templates tab.
"""

from timeline.tiles.tile import (
    MAX_TILE_SAMPLES,
    GeneratorTile,
    SampledTile,
    SplineTile,
    Tile,
    generator,
    spline,
)
from timeline.tiles.vibration_tile import VibrationTile

__all__ = [
    "GeneratorTile",
    "MAX_TILE_SAMPLES",
    "SampledTile",
    "SplineTile",
    "Tile",
    "VibrationTile",
    "generator",
    "spline",
]
