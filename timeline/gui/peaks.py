"""Min/max peak summaries per zoom level, so long recordings draw as fast as short ones.

Qt-free. Level 0 holds min/max per BASE samples, each further level per FACTOR times more (the
Audacity summary idea, whose first summary is also per 256 samples); a query picks the coarsest
level that still has two blocks per column, or the samples themselves below that. The samples
are referenced, not copied, and the levels are float32 (an hour at 44.1 kHz adds 2 x 2.5 MB for
the first level and 1/7 of that for the rest), built in chunks without a full-size temporary, and
a query reduces only the blocks its columns cover (at most 2 x BASE samples per column), so a
paint costs the same at every zoom.
"""

from __future__ import annotations

from collections import OrderedDict

import numpy as np

BASE = 256
FACTOR = 8
CHUNK = BASE << 12  # samples summarised at a time while building the first level


class PeakPyramid:
    """Min/max summaries of one array of samples."""

    def __init__(self, data: np.ndarray) -> None:
        self.data = np.asarray(data)
        self.levels: list[tuple[int, np.ndarray, np.ndarray]] = []  # (block size, mins, maxs)
        if len(self.data) <= 2 * BASE:
            return
        lo, hi = _first_level(self.data)
        block = BASE
        self.levels.append((block, lo, hi))
        while len(lo) > 2 * BASE:
            edges = np.arange(0, len(lo), FACTOR)
            lo, hi = np.minimum.reduceat(lo, edges), np.maximum.reduceat(hi, edges)
            block *= FACTOR
            self.levels.append((block, lo, hi))

    def __len__(self) -> int:
        return len(self.data)

    def columns(self, first: float, last: float, count: int) -> tuple[np.ndarray, np.ndarray]:
        """Min and max of samples [first, last) split into `count` equal columns."""
        count = max(1, int(count))
        edges = np.linspace(first, last, count + 1)
        per_column = (last - first) / count
        block, lo, hi = 1, self.data, self.data
        for size, level_lo, level_hi in self.levels:
            if size * 2 > per_column:
                break
            block, lo, hi = size, level_lo, level_hi
        idx = np.clip(np.floor(edges / block).astype(np.int64), 0, len(lo) - 1)
        ends = np.clip(np.ceil(edges[1:] / block).astype(np.int64), 1, len(lo))
        starts = idx[:-1]
        ends = np.maximum(ends, starts + 1)
        if per_column < block:
            return lo[starts], hi[starts]
        # reduceat runs each reduction to the next start and the last to the array's end: cut the
        # arrays at the last column's end so a query never reduces past what it shows
        stop = int(ends[-1])
        return np.minimum.reduceat(lo[:stop], starts), np.maximum.reduceat(hi[:stop], starts)


def _first_level(data: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Min and max per BASE samples as float32, made CHUNK samples at a time (no full-size
    temporary: an hour of samples is 0.6-1.3 GB)."""
    count = -(-len(data) // BASE)
    lo = np.empty(count, dtype=np.float32)
    hi = np.empty(count, dtype=np.float32)
    edges = np.arange(0, CHUNK, BASE)
    for first in range(0, len(data), CHUNK):
        chunk = data[first : first + CHUNK]
        starts = edges[: -(-len(chunk) // BASE)]  # the last block may be partial
        at = first // BASE
        lo[at : at + len(starts)] = np.minimum.reduceat(chunk, starts)
        hi[at : at + len(starts)] = np.maximum.reduceat(chunk, starts)
    return lo, hi


class PyramidCache:
    """Pyramids by tile key, least recently used dropped first."""

    def __init__(self, size: int = 64) -> None:
        self.size = size
        self._items: OrderedDict[str, PeakPyramid] = OrderedDict()

    def get(self, key: str, make) -> PeakPyramid:
        """The pyramid for key, built with make() the first time."""
        found = self._items.get(key)
        if found is None:
            found = self._items[key] = PeakPyramid(make())
            while len(self._items) > self.size:
                self._items.popitem(last=False)
        self._items.move_to_end(key)
        return found
