"""A signal cut into short overlapping frames: level, peak and frequency per frame."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.lib.stride_tricks import sliding_window_view

FRAME = 0.020  # s: long enough for a cycle at 50 Hz, short against touch's temporal resolution
HOP = 0.010  # s


@dataclass(frozen=True)
class Frames:
    """Per-frame RMS, peak and frequency of a signal sampled at `rate`.

    Frame i covers samples [i*hop, i*hop + size); `start` is the signal's first position. The
    frequency comes from the spacing of the zero crossings inside the frame (interpolated
    between samples); a frame with fewer than two crossings reports 0.
    """

    rms: np.ndarray
    peak: np.ndarray
    frequency: np.ndarray  # Hz
    size: int
    hop: int
    rate: float
    start: float

    def span(self, first: int, last: int) -> tuple[float, float]:
        """Positions covered by frames first..last (inclusive)."""
        return (
            self.start + first * self.hop / self.rate,
            self.start + (last * self.hop + self.size) / self.rate,
        )


def crossings(x: np.ndarray) -> np.ndarray:
    """Sample positions (fractional) where the signal changes sign."""
    j = np.flatnonzero(np.signbit(x[1:]) != np.signbit(x[:-1]))
    step = x[j] - x[j + 1]
    frac = np.divide(x[j], step, out=np.zeros_like(step), where=step != 0)
    return j + frac


def frames(signal: np.ndarray, rate: float, start: float = 0.0) -> Frames:
    """Cut a signal into FRAME-long frames every HOP (one frame if shorter)."""
    x = np.asarray(signal, dtype=np.float64)
    size = max(2, round(FRAME * rate))
    hop = max(1, round(HOP * rate))
    if x.size < size:
        x = np.pad(x, (0, size - x.size))
    with np.errstate(over="ignore"):  # a design at 1e300: its power is infinite, not a warning
        power = sliding_window_view(x * x, size)[::hop].mean(axis=1)
    peak = sliding_window_view(np.abs(x), size)[::hop].max(axis=1)
    where = np.append(crossings(x), np.inf)  # a sentinel keeps every index in range
    firsts = np.arange(power.size) * hop
    i0 = np.searchsorted(where, firsts)
    i1 = np.searchsorted(where, firsts + size - 1) - 1
    count = i1 - i0
    ok = count >= 1
    with np.errstate(invalid="ignore", divide="ignore"):
        spread = where[np.maximum(i1, 0)] - where[np.minimum(i0, where.size - 1)]
        frequency = np.where(ok, count * rate / (2.0 * spread), 0.0)
    return Frames(np.sqrt(power), peak, frequency, size, hop, rate, start)
