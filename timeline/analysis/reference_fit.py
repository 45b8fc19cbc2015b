"""A reference design against our analysis: which of its points an analysis made, at what gain.

An analysis puts every amplitude breakpoint on a sample of the sound (the follower is read after
a whole sample); a point drawn by hand in an editor falls between samples. At the analysis-made
points the reference's envelope is compared with ours, read without ducking: the reference's
emphasised points are un-ducked by its own `ducking` (Lofelt Studio's is 20 %: every emphasis
it made in the corpus pairs sits 0.800 above its breakpoint) and the least-squares gain from ours
to the reference is fitted. A gain of 1 with an error near 0 means the same analysis; another
gain with an error near 0 means the same analysis of the sound at a different level.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from timeline.analysis.agreement import on_grid

SAMPLE_GRID_TOLERANCE = 0.02  # samples: float32 times in a .haptic stay well within this
LOFELT_DUCKING = 20.0  # %: Lofelt Studio's breakpoint under an emphasis is 0.8 of the emphasis


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
