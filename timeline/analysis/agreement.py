"""How closely an analysis agrees with a reference design: the measures docs/convert.md reports.

Envelopes are compared on a 1 ms grid over the longer of the two designs, each read as straight
lines between its breakpoints (held at its last value): Pearson r and the mean absolute error of
the amplitude envelopes, and the mean absolute error of the frequency envelopes. Emphasis points
are matched one to one within 20 ms (greedy by distance) for the onset F1 score.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

GRID = 1e-3  # s
ONSET_TOLERANCE = 0.02  # s


@dataclass(frozen=True)
class Agreement:
    """Agreement of one analysis with its reference."""

    amplitude_r: float
    amplitude_mae: float
    onset_f1: float
    frequency_mae: float


def on_grid(points: np.ndarray, grid: np.ndarray) -> np.ndarray:
    """An envelope's (time, value) breakpoints as straight lines sampled on `grid`."""
    if len(points) == 0:
        return np.zeros(len(grid))
    return np.interp(grid, points[:, 0], points[:, 1])


def pearson(a: np.ndarray, b: np.ndarray) -> float:
    """Pearson correlation; 1.0 for two identical constants, 0.0 when only one is constant."""
    sa, sb = float(np.std(a)), float(np.std(b))
    if sa == 0.0 or sb == 0.0:
        return 1.0 if sa == sb and np.allclose(a, b) else 0.0
    return float(np.mean((a - a.mean()) * (b - b.mean())) / (sa * sb))


def onset_f1(found: np.ndarray, reference: np.ndarray, tolerance: float = ONSET_TOLERANCE) -> float:
    """F1 of found onset times against reference times, each matched at most once."""
    if len(found) == 0 and len(reference) == 0:
        return 1.0
    if len(found) == 0 or len(reference) == 0:
        return 0.0
    pairs = sorted(
        (abs(f - r), i, j)
        for i, f in enumerate(found)
        for j, r in enumerate(reference)
        if abs(f - r) <= tolerance
    )
    used_f: set[int] = set()
    used_r: set[int] = set()
    for _, i, j in pairs:
        if i not in used_f and j not in used_r:
            used_f.add(i)
            used_r.add(j)
    hits = len(used_f)
    precision, recall = hits / len(found), hits / len(reference)
    return 0.0 if hits == 0 else 2 * precision * recall / (precision + recall)


def agreement(
    amplitude: np.ndarray,
    frequency: np.ndarray,
    onsets: np.ndarray,
    ref_amplitude: np.ndarray,
    ref_frequency: np.ndarray,
    ref_onsets: np.ndarray,
) -> Agreement:
    """Compare envelopes ((n, 2) arrays) and emphasis times with a reference's."""
    end = max(amplitude[-1, 0], ref_amplitude[-1, 0])
    grid = np.arange(0.0, end + GRID / 2, GRID)
    a, ra = on_grid(amplitude, grid), on_grid(ref_amplitude, grid)
    f, rf = on_grid(frequency, grid), on_grid(ref_frequency, grid)
    return Agreement(
        amplitude_r=pearson(a, ra),
        amplitude_mae=float(np.mean(np.abs(a - ra))),
        onset_f1=onset_f1(np.asarray(onsets), np.asarray(ref_onsets)),
        frequency_mae=float(np.mean(np.abs(f - rf))),
    )
