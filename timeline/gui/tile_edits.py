"""Edits of a tile's shape from the waveform editor: pure functions like timeline.edits.

(Replacing a tile in the library is general enough to belong in timeline.edits; it lives here
until the core has it.)
"""

from __future__ import annotations

import math
from dataclasses import replace
from types import MappingProxyType

import numpy as np

from timeline import edits
from timeline.errors import EditError
from timeline.model import Project
from timeline.tiles import SampledTile, SplineTile, Tile

from .clip_shape import tile_samples

EDITABLE_POINTS = 12


def replace_tile(project: Project, tile_id: str, tile: Tile) -> Project:
    """Put a new shape under a tile id; refused if a clip would play past the new end."""
    project.tile(tile_id)
    for track in project.tracks:
        for clip in track.clips:
            if clip.tile_id == tile_id and clip.source_out > tile.duration * (1 + 1e-9):
                raise EditError(
                    f"a clip plays this tile up to {clip.source_out:.4g}; it cannot end at "
                    f"{tile.duration:.4g}"
                )
    return replace(project, tiles=MappingProxyType({**project.tiles, tile_id: tile}))


def _spline(project: Project, tile_id: str) -> SplineTile:
    tile = project.tile(tile_id)
    if not isinstance(tile, SplineTile):
        raise EditError(f"{tile.name} is not a spline; make an editable copy to change its points")
    return tile


def move_point(project: Project, tile_id: str, index: int, t: float, v: float) -> Project:
    """Move one control point to (t, v), kept between its neighbours and inside the tile."""
    tile = _spline(project, tile_id)
    points = list(tile.points)
    if not 0 <= index < len(points):
        raise EditError(f"the spline has no point {index + 1}")
    lo = points[index - 1][0] + 1e-6 if index > 0 else 0.0
    hi = points[index + 1][0] - 1e-6 if index + 1 < len(points) else tile.duration
    if not (math.isfinite(t) and math.isfinite(v)):
        raise EditError("a point needs finite numbers")
    points[index] = (min(max(t, lo), hi), v)
    return replace_tile(project, tile_id, replace(tile, points=tuple(points)))


def add_point(project: Project, tile_id: str, t: float, v: float) -> tuple[Project, int]:
    """Add a control point; returns its index."""
    tile = _spline(project, tile_id)
    if not 0.0 <= t <= tile.duration:
        raise EditError(f"a point must lie inside the tile (0 to {tile.duration:.4g})")
    if any(abs(p[0] - t) < 1e-6 for p in tile.points):
        raise EditError("there is already a point at that time")
    new = replace(tile, points=tile.points + ((t, v),))
    return replace_tile(project, tile_id, new), [p[0] for p in new.points].index(t)


def remove_point(project: Project, tile_id: str, index: int) -> Project:
    """Delete a control point (a spline keeps at least one)."""
    tile = _spline(project, tile_id)
    if len(tile.points) <= 1:
        raise EditError("a spline needs at least one point")
    if not 0 <= index < len(tile.points):
        raise EditError(f"the spline has no point {index + 1}")
    points = tile.points[:index] + tile.points[index + 1 :]
    return replace_tile(project, tile_id, replace(tile, points=points))


def editable_copy(project: Project, tile_id: str, tab: str = "Scratch") -> tuple[Project, str]:
    """A spline tile through EDITABLE_POINTS samples of any tile, added to a palette tab."""
    tile = project.tile(tile_id)
    ts = np.linspace(0.0, tile.duration, EDITABLE_POINTS)
    data, rate = tile_samples(tile, project.rate)
    vs = np.interp(ts * rate, np.arange(len(data)), data)
    points = tuple((float(t), float(v)) for t, v in zip(ts, vs, strict=True))
    return edits.add_tile(
        project, SplineTile(points, tile.duration, "natural", f"{tile.name} (edit)"), tab
    )


def range_tile(tile: Tile, a: float, b: float, rate: float) -> Tile:
    """The part [a, b) of a tile as a new tile starting at 0."""
    a, b = max(0.0, min(a, b)), min(tile.duration, max(a, b))
    if b - a <= 0:
        raise EditError("select a range of the tile first")
    name = f"{tile.name} {a:.3g}-{b:.3g}"
    if isinstance(tile, SplineTile):
        inside = [(t - a, v) for t, v in tile.points if a < t < b]
        ends = [
            (0.0, float(tile.evaluate(np.array([a]))[0])),
            (b - a, float(tile.evaluate(np.array([b]))[0])),
        ]
        return SplineTile(tuple(ends[:1] + inside + ends[1:]), b - a, tile.method, name)
    data, data_rate = tile_samples(tile, rate)
    return SampledTile(
        data[int(a * data_rate) : max(int(a * data_rate) + 1, int(b * data_rate))], data_rate, name
    )


def range_to_palette(
    project: Project, tile_id: str, a: float, b: float, tab: str = "Scratch"
) -> tuple[Project, str]:
    """Add the range [a, b) of a tile to a palette tab as a new tile."""
    return edits.add_tile(project, range_tile(project.tile(tile_id), a, b, project.rate), tab)
