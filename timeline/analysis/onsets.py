"""Emphasis: the amplitude peaks that start a sound's events, scored by spectral flux.

A breakpoint of the reduced amplitude envelope is a peak when it rises more than `minimum_rise`
above the breakpoint before it, the next breakpoint does not keep rising by more than `plateau`
% of that rise, and it comes at least `peak_window` after the last peak. Each peak's score is
the spectral flux at its time; `sensitivity` sets how much of the range between the weakest and
strongest score passes (0 % none, 100 % all). Kept peaks get an emphasis whose amplitude is the
peak's and whose frequency maps the score into sharpness_min..sharpness_max, and the envelope
under them is ducked by `ducking` % so the emphasis stands out.
"""

from __future__ import annotations

import numpy as np

from timeline.analysis.settings import AnalysisSettings


def peak_indices(t: np.ndarray, a: np.ndarray, settings: AnalysisSettings) -> np.ndarray:
    """Indices of the amplitude breakpoints that are peaks (see the module docstring)."""
    plateau = settings.plateau / 100.0
    peaks: list[int] = []
    previous = 0.0
    last_time = -np.inf
    for i in range(len(a) - 1):
        rise = a[i] - previous
        if (
            rise > settings.minimum_rise
            and (a[i] > a[i + 1] or a[i + 1] < a[i] + rise * plateau)
            and t[i] - last_time >= settings.peak_window
        ):
            peaks.append(i)
            last_time = t[i]
        previous = a[i]
    return np.array(peaks, dtype=np.intp)


def emphasis(
    t: np.ndarray,
    a: np.ndarray,
    flux_times: np.ndarray,
    flux: np.ndarray,
    settings: AnalysisSettings,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(indices, amplitudes, frequencies) of the emphasised breakpoints, and the ducked envelope.

    Returns the indices into t, each emphasis's amplitude and frequency; `a` is ducked in place.
    """
    on = settings.emphasis and settings.sensitivity > 0
    peaks = peak_indices(t, a, settings) if on else np.empty(0, dtype=np.intp)
    if len(peaks) == 0 or len(flux) == 0:
        return np.empty(0, dtype=np.intp), np.empty(0), np.empty(0)
    score = np.interp(t[peaks], flux_times, flux)
    lo, hi = float(score.min()), float(score.max())
    spread = hi - lo
    s = settings.sensitivity / 100.0
    threshold = (hi + spread * 1e-3) + s * (lo - (hi + spread * 1e-3))
    chosen = score >= threshold
    peaks, score = peaks[chosen], score[chosen]
    relative = (score - lo) / spread if spread > 0 else np.full(len(score), 0.5)
    freq = settings.sharpness_min + relative * (settings.sharpness_max - settings.sharpness_min)
    amp = a[peaks].copy()
    a[peaks] *= 1.0 - settings.ducking / 100.0
    return peaks, amp, freq
