"""The Templates tab: one tile of every generator, sized for the project's axis."""

from __future__ import annotations

import math

from timeline.signal.generators import GENERATORS
from timeline.signal.vibration_design import emphasis_length
from timeline.tiles import GeneratorTile, SplineTile, Tile

# Generators of one axis only: an emphasis is a burst of a carrier in Hz.
_TIME_ONLY = ("emphasis",)

# Per generator, parameters that make a useful starting shape on the time axis.
_TIME_PARAMS: dict[str, dict[str, float]] = {
    "sine": {"frequency": 10.0},
    "square": {"frequency": 10.0},
    "triangle": {"frequency": 10.0},
    "saw": {"frequency": 10.0},
    "chirp": {"f0": 5.0, "f1": 50.0},
    "noise": {"bandwidth": 50.0},
    "am": {"carrier": 175.0, "modulation": 8.0},
    "adsr": {"attack": 0.05, "decay": 0.1, "sustain": 0.6, "release": 0.2},
}


def template_tiles(axis: str) -> list[Tile]:
    """Tiles for the Templates tab: every generator plus a monotone spline bump."""
    span = 1.0 if axis == "time" else math.radians(90.0)
    tiles: list[Tile] = []
    for name in GENERATORS:
        if axis != "time" and name in _TIME_ONLY:
            continue
        params = _TIME_PARAMS.get(name, {}) if axis == "time" else {}
        if axis == "position" and name in ("sine", "square", "triangle", "saw"):
            params = {"frequency": 4.0 / span}
        length = span
        if name == "emphasis":  # as long as its pulse, so it reads back as an emphasis
            length = emphasis_length(GENERATORS[name].defaults["frequency"])
        tiles.append(GeneratorTile(name, length, tuple(params.items()), name))
    tiles.append(
        SplineTile(
            ((0.0, 0.0), (0.3 * span, 1.0), (0.7 * span, 1.0), (span, 0.0)), span, "pchip", "bump"
        )
    )
    return tiles
