"""The resolution setting: an editable number of breakpoints, at a bounded cost in error."""

from __future__ import annotations

import numpy as np

from tests.analysis.conftest import RATE, tone_bursts
from timeline.analysis import AnalysisSettings, analyse
from timeline.analysis.reduce import max_error, reduce_breakpoints


def test_slack_removes_points_only_within_its_error() -> None:
    t = np.arange(1000) / 1000
    v = np.exp(-t / 0.2) * (1 + 0.05 * np.sin(2 * np.pi * 7 * t))
    budget_only = reduce_breakpoints(t, v, budget=60)
    slack = reduce_breakpoints(t, v, budget=60, slack=0.01)
    assert len(slack) < len(budget_only) // 2
    assert max_error(t, v, slack) <= max(max_error(t, v, budget_only), 0.01) + 1e-12


def test_default_resolution_leaves_tens_of_points_a_second() -> None:
    onsets = list(np.arange(0.1, 5.0, 0.37))
    x = tone_bursts(onsets, 180.0, 5.0) + 0.002 * np.random.default_rng(2).normal(size=5 * RATE)
    fine = analyse(x, RATE, AnalysisSettings(resolution=100))
    edit = analyse(x, RATE)
    for envelope in ("amplitude", "frequency"):  # at most 30 a second each, against 60
        assert len(getattr(edit, envelope)) / 5.0 <= 30 < 60 <= len(getattr(fine, envelope)) / 5.0
    grid = np.arange(0, 5.0, 1e-3)
    fine_on, edit_on = (np.interp(grid, *a.amplitude.T) for a in (fine, edit))
    assert np.mean(np.abs(fine_on - edit_on)) < 0.01  # the cost, on average
    np.testing.assert_array_equal(edit.emphasis[:, 0], fine.emphasis[:, 0])  # same hits
