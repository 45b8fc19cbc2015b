"""Min/max peak summaries per zoom level, so long recordings draw as fast as short ones.

Qt-free. Level 0 holds min/max per BASE samples, each further level per FACTOR times more (the
Audacity summary idea); a query picks the coarsest level that still has two blocks per column.
The samples themselves are referenced, not copied, and the levels are float32 (an hour at
44.1 kHz adds 2 x 40 MB for the first level and 1/7 of that for the rest), and a query reduces
only the blocks its columns cover, so a paint costs the same at every zoom.
"""

from __future__ import annotations

from collections import OrderedDict

import numpy as np

BASE = 16
FACTOR = 8


class PeakPyramid:
    """Min/max summaries of one array of samples."""

    def __init__(self, data: np.ndarray) -> None:
        self.data = np.asarray(data)
        self.levels: list[tuple[int, np.ndarray, np.ndarray]] = []  # (block size, mins, maxs)
        lo = hi = self.data
        block = 1
        while len(lo) > 2 * BASE:
            step = BASE if block == 1 else FACTOR
            edges = np.arange(0, len(lo), step)
            lo = np.minimum.reduceat(lo, edges).astype(np.float32, copy=False)
            hi = np.maximum.reduceat(hi, edges).astype(np.float32, copy=False)
            block *= step
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
