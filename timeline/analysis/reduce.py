"""Breakpoint reduction: keep the points that carry an envelope's shape, within a budget.

Visvalingam-Whyatt simplification applied region by region (one second by default): in each
region the point whose triangle with its neighbours has the least area is removed, again and
again, until at most `budget` points remain; then points whose triangle is below `minimum_score`
(flat stretches, silence) go too. The first and last point of a region are always kept. With a
`tolerance`, a removal that would move the line further than that from any analysed point is
refused, so the result is bounded in error instead of in count. With `slack` (the analysis's
resolution setting), once the budget is met, points keep going while their removal leaves every
analysed point within `slack` of the line: the count stays within the budget and a smooth stretch
keeps only the few points its shape needs. `max_error` measures the bound.
"""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True)
def _area(t: np.ndarray, v: np.ndarray, a: int, b: int, c: int) -> float:
    return abs((t[a] - t[b]) * (v[c] - v[b]) - (t[c] - t[b]) * (v[a] - v[b]))


@njit(cache=True)
def _error_without(t: np.ndarray, v: np.ndarray, left: int, right: int) -> float:
    """Largest distance of the points between left and right from the line joining them."""
    worst = 0.0
    span = t[right] - t[left]
    for i in range(left + 1, right):
        f = (t[i] - t[left]) / span if span > 0 else 0.0
        worst = max(worst, abs(v[i] - (v[left] + f * (v[right] - v[left]))))
    return worst


@njit(cache=True)
def _less(area: np.ndarray, a: int, b: int) -> bool:
    """Heap order of points a and b: by area, then by index."""
    if area[a] != area[b]:
        return area[a] < area[b]
    return a < b


@njit(cache=True)
def _sift_up(heap: np.ndarray, place: np.ndarray, area: np.ndarray, i: int) -> None:
    point = heap[i]
    while i > 0:
        parent = (i - 1) // 2
        if not _less(area, point, heap[parent]):
            break
        heap[i] = heap[parent]
        place[heap[i]] = i
        i = parent
    heap[i] = point
    place[point] = i


@njit(cache=True)
def _sift_down(heap: np.ndarray, place: np.ndarray, area: np.ndarray, i: int, size: int) -> None:
    point = heap[i]
    while True:
        child = 2 * i + 1
        if child >= size:
            break
        if child + 1 < size and _less(area, heap[child + 1], heap[child]):
            child += 1
        if not _less(area, heap[child], point):
            break
        heap[i] = heap[child]
        place[heap[i]] = i
        i = child
    heap[i] = point
    place[point] = i


@njit(cache=True)
def _reduce_region(
    t: np.ndarray, v: np.ndarray, budget: int, minimum_score: float, tolerance: float, slack: float
) -> np.ndarray:
    n = t.shape[0]
    keep = np.ones(n, dtype=np.bool_)
    if n < 3:
        return keep
    prev = np.arange(-1, n - 1)
    nxt = np.arange(1, n + 1)
    # a min-heap of the inner points still to consider, by (area with the neighbours, index);
    # `place` is each point's position in it (-1: not in it), so a point whose neighbour goes
    # has its area changed where it stands
    area = np.zeros(n)
    place = np.full(n, -1, dtype=np.int64)
    heap = np.empty(n, dtype=np.int64)
    size = n - 2
    for i in range(1, n - 1):
        area[i] = _area(t, v, i - 1, i, i + 1)
        heap[i - 1] = i
        place[i] = i - 1
    for i in range(size // 2 - 1, -1, -1):
        _sift_down(heap, place, area, i, size)
    count = n
    while size > 0:
        mid = heap[0]
        size -= 1
        place[mid] = -1
        if size > 0:
            heap[0] = heap[size]
            _sift_down(heap, place, area, 0, size)
        left, right = prev[mid], nxt[mid]
        if tolerance < 0 and count <= budget and area[mid] >= minimum_score:
            if slack <= 0:
                break
            if _error_without(t, v, left, right) > slack:
                continue  # needed to stay within the slack; a later point may still go
        if tolerance >= 0 and _error_without(t, v, left, right) > tolerance:
            continue  # this point is needed to stay within the tolerance
        keep[mid] = False
        count -= 1
        nxt[left] = right
        prev[right] = left
        for m in (left, right):
            if 0 < m < n - 1:
                area[m] = _area(t, v, prev[m], m, nxt[m])
                if place[m] < 0:
                    place[m] = size
                    heap[size] = m
                    size += 1
                    _sift_up(heap, place, area, size - 1)
                else:
                    _sift_up(heap, place, area, int(place[m]))
                    _sift_down(heap, place, area, int(place[m]), size)
    return keep


def reduce_breakpoints(
    t: np.ndarray,
    v: np.ndarray,
    *,
    budget: int,
    region: float = 1.0,
    minimum_score: float = 0.0,
    tolerance: float | None = None,
    origin: float | None = None,
    slack: float = 0.0,
) -> np.ndarray:
    """Indices of the breakpoints (t ascending) kept: at most `budget` per `region` seconds.

    Regions start at `origin` (default: the first time). With `tolerance`, the count budget gives
    way to the error bound: no analysed point ends up further than `tolerance` from the line.
    With `slack`, points within the budget go too while no analysed point moves further than
    `slack` from the line by their removal.
    """
    t = np.ascontiguousarray(t, dtype=np.float64)
    v = np.ascontiguousarray(v, dtype=np.float64)
    if len(t) == 0:
        return np.empty(0, dtype=np.intp)
    start = t[0] if origin is None else origin
    bounds = start + region * np.arange(1, int((t[-1] - start) / region) + 2)
    cuts = np.concatenate([[0], np.searchsorted(t, bounds, side="left"), [len(t)]])
    cuts = np.unique(cuts)
    bound = -1.0 if tolerance is None else float(tolerance)
    kept = [
        a + np.flatnonzero(_reduce_region(t[a:b], v[a:b], budget, minimum_score, bound, slack))
        for a, b in zip(cuts[:-1], cuts[1:], strict=True)
        if b > a
    ]
    return np.concatenate(kept)


def max_error(t: np.ndarray, v: np.ndarray, kept: np.ndarray) -> float:
    """The largest distance of any analysed point from the line through the kept points."""
    if len(kept) == 0:
        return 0.0
    return float(np.max(np.abs(np.interp(t, t[kept], v[kept]) - v)))


class RegionReducer:
    """Reduces breakpoints region by region as they arrive, holding only the unfinished region."""

    def __init__(
        self, budget: int, minimum_score: float, tolerance: float | None, slack: float = 0.0
    ) -> None:
        self.options = {
            "budget": budget, "minimum_score": minimum_score, "tolerance": tolerance,
            "slack": slack,
        }  # fmt: skip
        self.origin: float | None = None
        self.pending_t = np.empty(0)
        self.pending_v = np.empty(0)
        self.done_t: list[np.ndarray] = []
        self.done_v: list[np.ndarray] = []

    def add(self, t: np.ndarray, v: np.ndarray) -> None:
        """Take the next breakpoints (later than any before) and reduce the regions they finish."""
        if len(t) == 0:
            return
        if self.origin is None:
            self.origin = float(t[0])
        self.pending_t = np.concatenate([self.pending_t, t])
        self.pending_v = np.concatenate([self.pending_v, v])
        finished = self.origin + np.floor(self.pending_t[-1] - self.origin)
        cut = int(np.searchsorted(self.pending_t, finished, side="left"))
        if cut > 0:
            self._reduce(self.pending_t[:cut], self.pending_v[:cut])
            self.pending_t, self.pending_v = self.pending_t[cut:], self.pending_v[cut:]

    def _reduce(self, t: np.ndarray, v: np.ndarray) -> None:
        kept = reduce_breakpoints(t, v, origin=self.origin, **self.options)
        self.done_t.append(t[kept])
        self.done_v.append(v[kept])

    def finish(self) -> tuple[np.ndarray, np.ndarray]:
        """All kept breakpoints: times and values."""
        if len(self.pending_t):
            self._reduce(self.pending_t, self.pending_v)
            self.pending_t = self.pending_v = np.empty(0)
        if not self.done_t:
            return np.empty(0), np.empty(0)
        return np.concatenate(self.done_t), np.concatenate(self.done_v)
