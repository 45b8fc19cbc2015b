"""A reference design against our analysis: which of its points an analysis made, at what gain.

An analysis puts every amplitude breakpoint on a sample of the sound (the follower is read after
a whole sample); a point drawn by hand in an editor falls between samples. At the analysis-made
points the reference's envelope is compared with ours, read without ducking: the reference's
emphasised points are un-ducked by its own `ducking` (Lofelt Studio's is 20 %: every emphasis
it made in the corpus pairs sits 0.800 above its breakpoint) and the least-squares gain from ours
to the reference is fitted. A gain of 1 with an error near 0 means the same analysis; another
gain with an error near 0 means the same analysis of the sound at a different level.

The same test sorts the reference's emphasis: one its analysis made sits on a sample, on a
breakpoint ducked by exactly `ducking`, with a frequency the flux mapping gave; a frequency on a
round value (a multiple of 0.05, as Lofelt Studio's default 0.5 or a designer's 0.9) was set in
the editor. `scored_where_made` measures agreement only on the reference's segments whose both
ends its analysis made, so hand-drawn points do not count against an analysis.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from timeline.analysis.agreement import on_grid, pearson

SAMPLE_GRID_TOLERANCE = 0.02  # samples: float32 times in a .haptic stay well within this
LOFELT_DUCKING = 20.0  # %: Lofelt Studio's breakpoint under an emphasis is 0.8 of the emphasis
ROUND_STEP = (
    0.05  # an emphasis frequency on a multiple of this was typed or defaulted, not analysed
)
VALUE_TOLERANCE = 1e-4  # float32 values in a .haptic stay well within this


@dataclass(frozen=True)
class ReferenceFit:
    """Our unducked envelope against a reference's analysis-made breakpoints."""

    analysis_points: int  # reference breakpoints on the sound's samples
    hand_placed: int  # reference breakpoints between samples
    gain: float  # least-squares gain from ours to the reference there (0 if none)
    error: float  # median absolute error there after that gain (0 if none)


def on_samples(times: np.ndarray, rate: float) -> np.ndarray:
    """Which times fall on a sample of a sound at `rate` (an analysis's, not a hand's)."""
    samples = np.asarray(times, dtype=np.float64) * rate
    return np.abs(samples - np.round(samples)) <= SAMPLE_GRID_TOLERANCE


def fit_reference(
    unducked: np.ndarray,
    reference: np.ndarray,
    emphasised: np.ndarray,
    rate: float,
    ducking: float = LOFELT_DUCKING,
) -> ReferenceFit:
    """Fit our envelope without ducking ((n, 2) breakpoints) to a reference's analysis points.

    `reference` is the reference's (m, 2) amplitude breakpoints, `emphasised` marks those that
    carry an emphasis (ducked by `ducking` % in the reference).
    """
    made = on_samples(reference[:, 0], rate)
    values = np.where(emphasised, reference[:, 1] / (1.0 - ducking / 100.0), reference[:, 1])
    ref, ours = values[made], on_grid(unducked, reference[made, 0])
    power = float(np.dot(ours, ours))
    if power == 0.0:
        return ReferenceFit(int(made.sum()), int((~made).sum()), 0.0, 0.0)
    gain = float(np.dot(ours, ref)) / power
    error = float(np.median(np.abs(gain * ours - ref)))
    return ReferenceFit(int(made.sum()), int((~made).sum()), gain, error)


def made_emphasis(emphasis: np.ndarray, rate: float, ducking: float = LOFELT_DUCKING) -> np.ndarray:
    """Which of a reference's emphasis ((k, 4): time, amplitude, frequency, the breakpoint's
    value) its analysis made: on a sample, ducked by `ducking`, at an unrounded frequency."""
    e = np.asarray(emphasis, dtype=np.float64).reshape(-1, 4)
    ducked = np.abs(e[:, 3] - e[:, 1] * (1.0 - ducking / 100.0)) <= VALUE_TOLERANCE
    steps = e[:, 2] / ROUND_STEP
    rounded = np.abs(steps - np.round(steps)) <= VALUE_TOLERANCE / ROUND_STEP
    return on_samples(e[:, 0], rate) & ducked & ~rounded


@dataclass(frozen=True)
class ScoredWhereMade:
    """Agreement on the grid points inside the reference's analysis-made segments."""

    share: float  # of the reference's span
    amplitude_r: float  # nan where the reference is flat there
    amplitude_mae: float


def scored_where_made(
    ours: np.ndarray, reference: np.ndarray, rate: float, gain: float = 1.0, grid: float = 1e-3
) -> ScoredWhereMade:
    """Pearson r and MAE of `gain` x our amplitude envelope against the reference's, both
    (n, 2) breakpoints, on the 1 ms grid points whose reference segment ends on two samples."""
    made = on_samples(reference[:, 0], rate)
    points = np.arange(0.0, reference[-1, 0] + grid / 2, grid)
    k = np.clip(np.searchsorted(reference[:, 0], points, side="right") - 1, 0, len(reference) - 2)
    inside = made[k] & made[k + 1]
    if not inside.any():
        return ScoredWhereMade(0.0, float("nan"), float("nan"))
    a = gain * on_grid(ours, points[inside])
    b = on_grid(reference, points[inside])
    if np.ptp(b) == 0.0:  # a flat stretch (silence): r says nothing
        return ScoredWhereMade(float(inside.mean()), float("nan"), float(np.mean(np.abs(a - b))))
    return ScoredWhereMade(float(inside.mean()), pearson(a, b), float(np.mean(np.abs(a - b))))
