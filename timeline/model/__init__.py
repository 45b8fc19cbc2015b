"""The project state: immutable tracks, clips, tiles, palette, variants, markers.

project holds the state's types; markers the markers and loop region; id_sequence the palette
tabs' persistent id lists; picture a project drawn as SVG (what a notebook shows). Every change
of state is an edit (timeline.edits).
"""

from timeline.model.markers import LoopRegion, Marker
from timeline.model.project import (
    AXES,
    DEFAULT_POSITION_RATE,
    DEFAULT_TIME_RATE,
    FADE_SHAPES,
    STRETCH_MODES,
    Clip,
    Fade,
    PaletteTab,
    Project,
    Track,
    Variant,
    map_changes,
)

__all__ = [
    "AXES",
    "Clip",
    "DEFAULT_POSITION_RATE",
    "DEFAULT_TIME_RATE",
    "FADE_SHAPES",
    "Fade",
    "LoopRegion",
    "Marker",
    "PaletteTab",
    "Project",
    "STRETCH_MODES",
    "Track",
    "Variant",
    "map_changes",
]
