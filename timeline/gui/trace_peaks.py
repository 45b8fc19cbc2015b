"""A rendered trace ready to draw at any zoom: its lowest and highest value per cell of the axis,
and per 4, 16, 64 ... cells (Qt-free: the findings worker builds it, off the GUI thread).

Drawing then costs only what is visible: for a range of pixel columns, the coarsest level whose
cells are no wider than a pixel is cut to that range and reduced to one low and one high per
column (`columns`). A time trace has one cell per sample; a position trace (torque against the
knob's angle) has one cell per table step, holding every sample rendered at that angle.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

FACTOR = 4  # cells merged per level


@dataclass(frozen=True, eq=False)
class Peaks:
    """Lowest and highest value per cell of `step` axis units from `start`, at every level
    (level k: cells of FACTOR**k steps); NaN in a cell nothing was rendered in."""

    start: float
    step: float
    levels: tuple[tuple[np.ndarray, np.ndarray], ...]

    @classmethod
    def of(cls, x: np.ndarray, values: np.ndarray, step: float, uniform: bool) -> Peaks:
        """Peaks of `values` at axis positions `x`: `uniform` when x[i] = x[0] + i*step (a time
        trace), else each value goes to the cell of its position (an angle, in any order)."""
        start = float(x[0] if uniform else np.min(x))
        if uniform:
            lows = highs = np.asarray(values, dtype=np.float64)
        else:
            cells = np.floor((x - start) / step).astype(np.int64)
            lows = np.full(int(cells.max()) + 1, np.nan)
            highs = lows.copy()
            np.fmin.at(lows, cells, values)
            np.fmax.at(highs, cells, values)
        levels = [(lows, highs)]
        while lows.size > 1:
            pad = -lows.size % FACTOR
            lows = np.fmin.reduce(np.r_[lows, [np.nan] * pad].reshape(-1, FACTOR), axis=1)
            highs = np.fmax.reduce(np.r_[highs, [np.nan] * pad].reshape(-1, FACTOR), axis=1)
            levels.append((lows, highs))
        return cls(start, float(step), tuple(levels))

    @property
    def stop(self) -> float:
        """The axis position where the last cell ends."""
        return self.start + self.levels[0][0].size * self.step

    def columns(
        self, px_per_unit: float, x_from: float, x_to: float
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Between scene x `x_from` and `x_to` (pixels, x = axis * px_per_unit): each column's x,
        lowest and highest value (NaN: nothing there). Below a pixel per cell one entry per pixel
        column; above it one per cell, at the cell's start."""
        level = 0
        while (
            level + 1 < len(self.levels) and px_per_unit * self.step * FACTOR ** (level + 1) <= 1.0
        ):
            level += 1
        lows, highs = self.levels[level]
        width = self.step * FACTOR**level
        first = max(0, math.floor((x_from / px_per_unit - self.start) / width))
        last = min(lows.size, math.ceil((x_to / px_per_unit - self.start) / width) + 1)
        if last <= first:
            empty = np.zeros(0)
            return empty, empty, empty
        x = (self.start + np.arange(first, last) * width) * px_per_unit
        lows, highs = lows[first:last], highs[first:last]
        if px_per_unit * width >= 1.0:
            return x, lows, highs
        column = np.floor(x)
        starts = np.r_[0, np.flatnonzero(np.diff(column)) + 1]
        return column[starts], np.fmin.reduceat(lows, starts), np.fmax.reduceat(highs, starts)
