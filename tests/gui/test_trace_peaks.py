"""Peaks of a rendered trace: every zoom shows each pixel column's true lowest and highest value."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from timeline.gui.trace_peaks import Peaks


@settings(max_examples=60, deadline=None)
@given(
    n=st.integers(1, 3000),
    px=st.sampled_from([0.01, 0.3, 1.0, 7.0, 400.0]),
    seed=st.integers(0, 2**32 - 1),
    uniform=st.booleans(),
)
def test_every_value_is_drawn_in_a_column_just_left_of_it(
    n: int, px: float, seed: int, uniform: bool
) -> None:
    rng = np.random.default_rng(seed)
    step = 0.01
    x = 1.0 + step * np.arange(n) if uniform else rng.uniform(-0.5, 0.5 + n * step / 10, n)
    values = rng.normal(size=n)
    peaks = Peaks.of(x, values, step, uniform)
    cols, lows, highs = peaks.columns(px, peaks.start * px - 5.0, peaks.stop * px + 5.0)
    drawn = np.isfinite(lows)
    assert np.nanmin(lows) == values.min() and np.nanmax(highs) == values.max()
    assert (lows[drawn] <= highs[drawn]).all()
    span = (peaks.stop - peaks.start) * px
    assert drawn.sum() <= max(span, 0) / min(1.0, px * step) + 2  # no more than a column a pixel
    # each value lies between the low and the high of the column its cell (or merged cell, at
    # most a pixel wide) starts in: at most 2 px left of it, or at the cell's start when wider
    for xi, v in zip(x, values, strict=True):
        here = xi * px
        near = drawn & (cols <= here + 1e-9) & (cols >= here - max(2.0, px * step + 1.0))
        assert ((lows[near] <= v) & (v <= highs[near])).any()


def test_an_empty_range_and_gaps() -> None:
    peaks = Peaks.of(np.array([0.0, 0.05]), np.array([1.0, -1.0]), 0.01, uniform=False)
    assert peaks.columns(1000.0, 500.0, 600.0)[0].size == 0
    x, lows, highs = peaks.columns(1000.0, 0.0, 60.0)  # 10 px per cell: one entry per cell
    assert lows[0] == 1.0 and np.isnan(lows[1:5]).all() and highs[5] == -1.0
