"""Snapping a dragged position to clip edges and the ruler grid (Qt-free)."""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable

import numpy as np

from timeline.model import Project, Track


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


# a track's clip starts and ends, as arrays, when something already holds them (else None)
KnownEdges = Callable[[Track], "tuple[np.ndarray, np.ndarray] | None"]


class EdgeIndex:
    """Clip edges sorted once, so each drag step snaps by bisection instead of a walk.

    Each track's edges are sorted once per track object (edits share unchanged tracks), taken from
    `known` (the scene's lanes hold every track's starts and ends as arrays) when it has them,
    else from the clips. The tracks without an excluded clip are searched as one array, kept for
    as long as they are the same objects (a whole drag); a track holding an excluded clip is
    searched in its own array with the excluded clips' edges taken out.
    """

    def __init__(self, known: KnownEdges = lambda _track: None) -> None:
        self._known = known
        self._tracks: dict[str, tuple[Track, np.ndarray]] = {}  # track id -> its sorted edges
        self._others: tuple[Track, ...] | None = None
        self._edges = np.zeros(0)

    def nearest(self, project: Project, value: float, exclude: Iterable[str] = ()) -> float:
        """The clip edge (or the origin) nearest to value, ignoring the excluded clips."""
        skip = set(exclude)
        free = [t.clips_by_id.keys().isdisjoint(skip) for t in project.tracks]  # walks the fewer
        holding = [t for t, f in zip(project.tracks, free, strict=True) if not f]
        others = tuple(t for t, f in zip(project.tracks, free, strict=True) if f)
        if self._others is None or not _same_objects(others, self._others):
            self._others = others
            kept = self._tracks  # only the project's tracks stay
            self._tracks = {t.id: kept[t.id] for t in project.tracks if t.id in kept}
            runs = [self._sorted(t) for t in others]  # sorted runs: a stable sort merges them
            self._edges = np.sort(np.concatenate([np.zeros(0), *runs]), kind="stable")
        best = 0.0
        searched = [self._edges]
        for track in holding:
            left = [track.clips_by_id[i] for i in skip.intersection(track.clips_by_id)]
            edges = _without(self._sorted(track), [e for c in left for e in (c.start, c.end)])
            if edges is None:  # `known` disagreed with the clips: take them from the clips
                kept = (c for c in track.clips if c.id not in skip)
                edges = np.sort(np.array([e for c in kept for e in (c.start, c.end)]))
            searched.append(edges)
        for edges in searched:
            i = int(np.searchsorted(edges, value))
            for j in (i - 1, i):
                if 0 <= j < len(edges) and abs(edges[j] - value) < abs(best - value):
                    best = float(edges[j])
        return best

    def _sorted(self, track: Track) -> np.ndarray:
        """A track's clip edges in ascending order (kept while the track is the same object)."""
        kept = self._tracks.get(track.id)
        if kept is not None and kept[0] is track:
            return kept[1]
        arrays = self._known(track)
        if arrays is None:
            edges = np.array([e for c in track.clips for e in (c.start, c.end)], dtype=np.float64)
        else:
            edges = np.concatenate(arrays)
        edges.sort()
        self._tracks[track.id] = (track, edges)
        return edges


def _without(edges: np.ndarray, values: list[float]) -> np.ndarray | None:
    """Sorted `edges` less one occurrence of each of `values`; None if one is not there."""
    if not values:
        return edges
    drop = np.sort(np.array(values, dtype=np.float64))
    repeat = np.arange(drop.size) - np.searchsorted(drop, drop)  # the nth of equal values
    at = np.searchsorted(edges, drop) + repeat
    if at[-1] >= edges.size or not (edges[at] == drop).all():
        return None
    return np.delete(edges, at)


def _same_objects(a: tuple[object, ...], b: tuple[object, ...]) -> bool:
    return len(a) == len(b) and all(x is y for x, y in zip(a, b, strict=True))
