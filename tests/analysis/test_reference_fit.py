"""Telling an analysis-made reference breakpoint from a hand-drawn one, and fitting its gain."""

from __future__ import annotations

import numpy as np

from timeline.analysis.reference_fit import (
    fit_reference,
    made_emphasis,
    on_samples,
    scored_where_made,
)

RATE = 44_100


def test_times_on_samples_are_told_from_times_between_them() -> None:
    times = np.array([0.0, 45 / RATE, np.float32(2779 / RATE), 0.0045363220200873, 1.5 / RATE])
    assert on_samples(times, RATE).tolist() == [True, True, True, False, False]


def test_a_reference_at_half_our_level_with_ducked_emphasis_and_a_drawn_point() -> None:
    ours = np.array([[0.0, 0.0], [100 / RATE, 0.8], [200 / RATE, 0.4], [300 / RATE, 0.2]])
    reference = np.array(
        [
            [0.0, 0.0],
            [100 / RATE, 0.4 * 0.8],  # emphasised: ducked 20 % as Lofelt Studio does
            [150.5 / RATE, 0.9],  # drawn by hand between samples: not fitted
            [200 / RATE, 0.2],
            [300 / RATE, 0.1],
        ]
    )
    emphasised = np.array([False, True, False, False, False])
    fit = fit_reference(ours, reference, emphasised, RATE)
    assert (fit.analysis_points, fit.hand_placed) == (4, 1)
    assert abs(fit.gain - 0.5) < 1e-12 and fit.error < 1e-12
    # read without un-ducking, the emphasised point no longer fits
    assert fit_reference(ours, reference, emphasised, RATE, ducking=0.0).error > 0.0


def test_silence_fits_with_no_gain() -> None:
    silent = np.array([[0.0, 0.0], [1.0, 0.0]])
    fit = fit_reference(silent, np.array([[0.0, 0.3], [0.5, 0.3]]), np.zeros(2, bool), RATE)
    assert (fit.gain, fit.error, fit.analysis_points) == (0.0, 0.0, 2)


def test_emphasis_made_by_analysis_is_told_from_emphasis_set_in_the_editor() -> None:
    emphasis = np.array(
        [
            [100 / RATE, 0.5, 0.5083, 0.4],  # on a sample, ducked 20 %, an analysed frequency
            [200 / RATE, 0.5, 0.9, 0.4],  # ... but a frequency typed in the editor
            [300 / RATE, 0.5, 0.3217, 0.5],  # not ducked: added by hand on a breakpoint
            [350.5 / RATE, 0.5, 0.3217, 0.4],  # between samples: drawn by hand
        ]
    )
    assert made_emphasis(emphasis, RATE).tolist() == [True, False, False, False]
    assert made_emphasis(np.zeros((0, 4)), RATE).tolist() == []


def test_scoring_only_where_the_analysis_made_the_reference() -> None:
    ours = np.array([[0.0, 0.0], [100 / RATE, 1.0], [300 / RATE, 0.5], [400 / RATE, 0.0]])
    # the same envelope at half the level, with a point drawn by hand at 350.5 samples
    reference = np.array(
        [[0.0, 0.0], [100 / RATE, 0.5], [300 / RATE, 0.25], [350.5 / RATE, 0.9], [400 / RATE, 0]]
    )
    found = scored_where_made(ours, reference, RATE, gain=0.5, grid=1 / RATE)
    assert found.share == 300 / 401  # samples 0..299 of 0..400: before the drawn point
    assert found.amplitude_r > 1 - 1e-12 and found.amplitude_mae < 1e-12
    as_is = scored_where_made(ours, reference, RATE, grid=1 / RATE)
    assert as_is.amplitude_r > 1 - 1e-12 and 0.2 < as_is.amplitude_mae < 0.4
    drawn = np.array([[0.5 / RATE, 0.0], [99.5 / RATE, 1.0]])
    assert scored_where_made(ours, drawn, RATE).share == 0.0
