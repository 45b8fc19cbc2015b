"""Edits of a tile's shape (the waveform editor's): pure functions like timeline.edits."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from timeline import edits
from timeline.edits import replace_tile
from timeline.errors import EditError
from timeline.model import Project
from timeline.quality import preset
from timeline.tiles import SampledTile, SplineTile, Tile

EDITABLE_POINTS = 12


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
    if isinstance(tile, SampledTile):
        vs = np.interp(ts * tile.rate, np.arange(len(tile.data)), tile.data)
    else:
        vs = tile.evaluate(ts)
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
    if isinstance(tile, SampledTile):
        data, data_rate = tile.data, tile.rate
    else:
        n = max(1, math.ceil(tile.duration * rate))
        data, data_rate = tile.render(0.0, 1.0 / rate, n, preset("exact")), rate
    return SampledTile(
        data[int(a * data_rate) : max(int(a * data_rate) + 1, int(b * data_rate))], data_rate, name
    )


def range_to_palette(
    project: Project, tile_id: str, a: float, b: float, tab: str = "Scratch"
) -> tuple[Project, str]:
    """Add the range [a, b) of a tile to a palette tab as a new tile."""
    return edits.add_tile(project, range_tile(project.tile(tile_id), a, b, project.rate), tab)
