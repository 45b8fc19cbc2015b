"""Sampled-signal evaluation on an arithmetic grid: direct, linear, or band-limited (soxr)."""

from __future__ import annotations

import numpy as np

from timeline.quality import QualityPreset

# Samples of context kept either side of a segment so soxr's filter settles before the part used.
_SOXR_MARGIN = 256


def sample_grid(
    data: np.ndarray, rate: float, u0: float, du: float, n: int, quality: QualityPreset
) -> np.ndarray:
    """Values of a sampled signal (sample k at k/rate, zero outside) at u0 + i*du for i < n.

    A grid aligned to the samples is copied exactly; otherwise draft interpolates linearly and
    normal/exact resample band-limited with soxr, so shrinking a recording never aliases.
    """
    if n <= 0:
        return np.zeros(0)
    step = du * rate  # source samples per output sample
    start = u0 * rate
    if abs(step) == 1.0 and start == np.floor(start):
        if step > 0:
            return _take(data, int(start), n)
        return _take(data, int(start) - n + 1, n)[::-1].copy()
    if quality.resampler == "linear" or abs(step) < 1.0:
        # Upsampling (step < 1) adds no content above the source's Nyquist: interpolation suffices,
        # but for normal/exact use cubic to keep the passband flat.
        return _interpolate(data, start + step * np.arange(n), quality.fraction)
    return _band_limited(data, start, step, n, quality)


def _take(data: np.ndarray, first: int, n: int) -> np.ndarray:
    out = np.zeros(n)
    lo, hi = max(first, 0), min(first + n, len(data))
    if hi > lo:
        out[lo - first : hi - first] = data[lo:hi]
    return out


def _interpolate(data: np.ndarray, index: np.ndarray, method: str) -> np.ndarray:
    """Interpolate at fractional sample indices; zero outside [0, len-1]."""
    n = len(data)
    out = np.zeros(index.shape)
    inside = (index >= 0) & (index <= n - 1)
    if not inside.any():
        return out
    x = index[inside]
    if method == "cubic" and n >= 4:
        out[inside] = _catmull_rom(data, x)
    else:
        out[inside] = np.interp(x, np.arange(n), data)
    return out


def _catmull_rom(data: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Cubic (Catmull-Rom) interpolation at fractional indices inside the data."""
    n = len(data)
    i = np.clip(np.floor(x).astype(np.int64), 0, n - 2)
    t = x - i
    p0 = data[np.clip(i - 1, 0, n - 1)]
    p1 = data[i]
    p2 = data[i + 1]
    p3 = data[np.clip(i + 2, 0, n - 1)]
    return p1 + 0.5 * t * (
        p2 - p0 + t * (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3 + t * (3.0 * (p1 - p2) + p3 - p0))
    )


def _band_limited(
    data: np.ndarray, start: float, step: float, n: int, quality: QualityPreset
) -> np.ndarray:
    """Downsample by `step` source samples per output sample with soxr, then align sub-sample."""
    import soxr

    reverse = step < 0
    if reverse:
        # Evaluate the same points in ascending order and flip back.
        start = start + step * (n - 1)
        step = -step
    lo = int(np.floor(start)) - _SOXR_MARGIN
    hi = int(np.ceil(start + step * (n - 1))) + _SOXR_MARGIN + 1
    segment = _take(data, lo, hi - lo)
    soxr_quality = "VHQ" if quality.resampler == "soxr-vhq" else "HQ"
    resampled = soxr.resample(segment, 1.0, 1.0 / step, quality=soxr_quality)
    # resampled[j] sits at source index lo + j*step.
    index = (start - lo) / step + np.arange(n)
    out = _interpolate(resampled, index, quality.fraction)
    return out[::-1] if reverse else out
