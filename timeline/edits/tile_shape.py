"""Edits of a tile's shape (the waveform editor's): pure functions like timeline.edits."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from timeline import edits
from timeline.edits import replace_tile
from timeline.edits.naming import span_text, unique_tile_name
from timeline.errors import EditError
from timeline.model import Project
from timeline.signal.render_presets import preset
from timeline.tiles import SampledTile, SplineTile, Tile
from timeline.tiles.vibration_tile import VibrationTile

EDITABLE_POINTS = 12


AMPLITUDE = "amplitude"
FREQUENCY = "frequency"
LANES = (AMPLITUDE, FREQUENCY)  # a vibration design's envelopes, by the name the editor shows


def points_of(tile: Tile | None, lane: str = AMPLITUDE) -> tuple[tuple[float, float], ...] | None:
    """The points a designer drags in the waveform editor: a spline's control points, or one of a
    vibration design's envelopes (`lane`: amplitude or frequency breakpoints, 0..1); None for
    tiles without points."""
    if isinstance(tile, SplineTile):
        return tile.points
    if isinstance(tile, VibrationTile):
        return getattr(tile.design, _lane(lane))
    return None


def _lane(lane: str) -> str:
    if lane not in LANES:
        raise EditError(f"a design has no {lane!r} envelope (it has {' and '.join(LANES)})")
    return lane


def _points(project: Project, tile_id: str, lane: str) -> tuple[Tile, list[tuple[float, float]]]:
    tile = project.tile(tile_id)
    points = points_of(tile, lane)
    if points is None:
        raise EditError(f"{tile.name} is not a spline; make an editable copy to change its points")
    return tile, list(points)


def _with_points(tile: Tile, points: list[tuple[float, float]], lane: str) -> Tile:
    if isinstance(tile, VibrationTile):
        return replace(tile, design=replace(tile.design, **{_lane(lane): tuple(points)}))
    return replace(tile, points=tuple(points))


def _span(tile: Tile) -> float:
    """How far points may go: a spline's length, a design's (its emphasis may ring past it)."""
    return tile.design.duration if isinstance(tile, VibrationTile) else tile.duration


def _value(tile: Tile, v: float) -> float:
    """A dragged value as the tile takes it: a design's envelopes stay within 0..1."""
    return min(max(v, 0.0), 1.0) if isinstance(tile, VibrationTile) else v


def move_point(
    project: Project, tile_id: str, index: int, t: float, v: float, lane: str = AMPLITUDE
) -> Project:
    """Move one point to (t, v), kept between its neighbours and inside the tile.

    A spline's points stay 1 us apart; a design's breakpoints (of `lane`) may share a time (a
    step) and keep their values within 0..1."""
    tile, points = _points(project, tile_id, lane)
    if not 0 <= index < len(points):
        raise EditError(f"the tile has no point {index + 1}")
    gap = 0.0 if isinstance(tile, VibrationTile) else 1e-6
    lo = points[index - 1][0] + gap if index > 0 else 0.0
    hi = points[index + 1][0] - gap if index + 1 < len(points) else _span(tile)
    if not (math.isfinite(t) and math.isfinite(v)):
        raise EditError("a point needs finite numbers")
    points[index] = (min(max(t, lo), hi), _value(tile, v))
    return replace_tile(project, tile_id, _with_points(tile, points, lane))


def add_point(
    project: Project, tile_id: str, t: float, v: float, lane: str = AMPLITUDE
) -> tuple[Project, int]:
    """Add a point (to a design's `lane` envelope); returns its index."""
    tile, points = _points(project, tile_id, lane)
    if not 0.0 <= t <= _span(tile):
        raise EditError(f"a point must lie inside the tile (0 to {_span(tile):.4g})")
    if not (math.isfinite(t) and math.isfinite(v)):
        raise EditError("a point needs finite numbers")
    if any(abs(p[0] - t) < 1e-6 for p in points):
        raise EditError("there is already a point at that time")
    index = sum(1 for p in points if p[0] < t)
    points.insert(index, (t, _value(tile, v)))
    return replace_tile(project, tile_id, _with_points(tile, points, lane)), index


def remove_point(project: Project, tile_id: str, index: int, lane: str = AMPLITUDE) -> Project:
    """Delete a point (a tile keeps at least one)."""
    tile, points = _points(project, tile_id, lane)
    if len(points) <= 1:
        raise EditError("a tile's shape needs at least one point")
    if not 0 <= index < len(points):
        raise EditError(f"the tile has no point {index + 1}")
    del points[index]
    return replace_tile(project, tile_id, _with_points(tile, points, lane))


def editable_copy(project: Project, tile_id: str, tab: str = "Scratch") -> tuple[Project, str]:
    """A spline tile through EDITABLE_POINTS samples of any tile, added to a palette tab."""
    tile = project.tile(tile_id)
    ts = np.linspace(0.0, tile.duration, EDITABLE_POINTS)
    if isinstance(tile, SampledTile):
        vs = np.interp(ts * tile.rate, np.arange(len(tile.data)), tile.data)
    else:
        vs = tile.evaluate(ts)
    points = tuple((float(t), float(v)) for t, v in zip(ts, vs, strict=True))
    name = unique_tile_name(project, f"{tile.name} (edit)")
    return edits.add_tile(project, SplineTile(points, tile.duration, "natural", name), tab)


def range_tile(tile: Tile, a: float, b: float, rate: float, name: str = "") -> Tile:
    """The part [a, b) of a tile as a new tile starting at 0 (named after the range in seconds
    unless a name is given)."""
    a, b = max(0.0, min(a, b)), min(tile.duration, max(a, b))
    if b - a <= 0:
        raise EditError("select a range of the tile first")
    name = name or f"{tile.name} {span_text(a, b, 'time')}"
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
    """Add the range [a, b) of a tile to a palette tab as a new tile, named after the range in
    the project's display units ("four detents 20-260 deg")."""
    tile = project.tile(tile_id)
    lo, hi = max(0.0, min(a, b)), min(tile.duration, max(a, b))
    name = unique_tile_name(project, f"{tile.name} {span_text(lo, hi, project.axis)}")
    return edits.add_tile(project, range_tile(tile, a, b, project.rate, name), tab)
