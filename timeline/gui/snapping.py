"""Snapping a dragged position to clip edges and the ruler grid (Qt-free)."""

from __future__ import annotations

import math
from collections.abc import Iterable

import numpy as np

from timeline.model import Clip, Project, Track


def snap(value: float, edges: Iterable[float], grid: float, tolerance: float) -> float:
    """The nearest clip edge within tolerance, else the nearest grid line within it, else value."""
    best = min(edges, key=lambda e: abs(e - value), default=None)
    if best is not None and abs(best - value) <= tolerance:
        return best
    if grid > 0:
        line = round(value / grid) * grid
        if abs(line - value) <= tolerance and math.isfinite(line):
            return line
    return value


class EdgeIndex:
    """Clip edges sorted once, so each drag step snaps by bisection instead of a walk.

    The tracks without a dragged clip keep their edges in one sorted array for as long as they
    are the same objects (edits share unchanged tracks, so for a whole drag); only the tracks
    holding a dragged clip are gathered again, without it, and their edges sorted again only when
    one of those other clips changed.
    """

    def __init__(self) -> None:
        self._others: tuple[Track, ...] | None = None
        self._edges = np.zeros(0)
        self._mine: tuple[Clip, ...] = ()  # the other clips of the dragged clips' tracks
        self._own = np.zeros(0)

    def nearest(self, project: Project, value: float, exclude: Iterable[str] = ()) -> float:
        """The clip edge (or the origin) nearest to value, ignoring the excluded clips."""
        skip = set(exclude)
        holding = [t for t in project.tracks if any(c in t.clips_by_id for c in skip)]
        others = tuple(t for t in project.tracks if not any(t is h for h in holding))
        if self._others is None or not _same_objects(others, self._others):
            self._others = others
            self._edges = _sorted_edges(c for t in others for c in t.clips)
        mine = tuple(c for t in holding for c in t.clips if c.id not in skip)
        if not _same_objects(mine, self._mine):  # a drag replaces only the dragged clips
            self._mine, self._own = mine, _sorted_edges(mine)
        own = self._own
        best = 0.0
        for edges in (self._edges, own):
            i = int(np.searchsorted(edges, value))
            for j in (i - 1, i):
                if 0 <= j < len(edges) and abs(edges[j] - value) < abs(best - value):
                    best = float(edges[j])
        return best


def _same_objects(a: tuple[object, ...], b: tuple[object, ...]) -> bool:
    return len(a) == len(b) and all(x is y for x, y in zip(a, b, strict=True))


def _sorted_edges(clips: Iterable[Clip]) -> np.ndarray:
    return np.sort(np.array([e for c in clips for e in (c.start, c.end)], dtype=np.float64))
