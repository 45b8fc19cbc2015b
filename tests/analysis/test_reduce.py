"""Breakpoint reduction: the shape kept within a budget per second, or within an error bound."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from timeline.analysis.reduce import RegionReducer, max_error, reduce_breakpoints


def test_ramp_and_hold_keep_their_corners() -> None:
    t = np.arange(10) / 10
    v = np.array([0, 0, 0, 0.25, 0.5, 0.75, 1, 1, 0.5, 1.0])
    kept = reduce_breakpoints(t, v, budget=6)
    assert kept.tolist() == [0, 2, 6, 7, 8, 9]
    assert max_error(t, v, kept) < 1e-12  # the removed points lay on the kept lines


def test_budget_is_per_region_and_keeps_region_edges() -> None:
    t = np.arange(3000) / 1000.0  # 3 s at 1 ms
    v = np.abs(np.sin(2 * np.pi * 7 * t))
    kept = reduce_breakpoints(t, v, budget=60)
    counts = np.histogram(t[kept], bins=[0, 1, 2, 3.001])[0]
    assert counts.tolist() == [60, 60, 60]
    assert {0, 999, 1000, 1999, 2000, 2999} <= set(kept.tolist())


def test_flat_silence_drops_to_its_ends() -> None:
    t = np.arange(500) / 1000.0
    kept = reduce_breakpoints(t, np.zeros(500), budget=60, minimum_score=1e-8)
    assert kept.tolist() == [0, 499]


@settings(max_examples=60, deadline=None)
@given(
    st.lists(st.floats(0, 1), min_size=3, max_size=300),
    st.floats(0.001, 0.3),
)
def test_tolerance_bounds_the_error(values: list[float], tolerance: float) -> None:
    v = np.array(values)
    t = np.arange(len(v)) * 0.01
    kept = reduce_breakpoints(t, v, budget=2, tolerance=tolerance)
    assert kept[0] == 0 and kept[-1] == len(v) - 1
    assert max_error(t, v, kept) <= tolerance + 1e-12


def test_streamed_regions_equal_one_pass() -> None:
    t = np.arange(1, 2501) / 1000.0
    v = np.random.default_rng(1).random(len(t))
    r = RegionReducer(60, 1e-8, None)
    for i in range(0, len(t), 333):
        r.add(t[i : i + 333], v[i : i + 333])
    st_, sv = r.finish()
    kept = reduce_breakpoints(t, v, budget=60, minimum_score=1e-8)
    np.testing.assert_array_equal(st_, t[kept])
    np.testing.assert_array_equal(sv, v[kept])
