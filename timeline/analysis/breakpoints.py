"""Drive waveforms analysed into envelope breakpoints, and breakpoint reduction to an error bound.

Used where a drive layer is not (or no longer) envelope data: sampled recordings, generators,
overlapping or looped clips. A local least-squares carrier estimate gives the frequency and a
quadrature envelope the amplitude, on a GRID-second grid; both are then reduced to the fewest
breakpoints whose straight segments stay within a stated tolerance (Douglas-Peucker).
"""

from __future__ import annotations

import numpy as np

from timeline.signal.vibration_design import F_MAX, F_MIN, carrier_hz, normalised_frequency

AMPLITUDE_TOLERANCE = 0.01  # analysed envelope breakpoints reproduce the analysed envelope to this
FREQUENCY_TOLERANCE = 0.02
GRID = 0.001  # s between analysed envelope samples before reduction
ANALYSIS_WINDOW = 0.01  # s: carrier frequency window (about one period at F_MIN)

MEDIAN_BLOCK = 2**20  # envelope samples copied into windows for one median call

Points = list[tuple[float, float]]


def _window_sum(values: np.ndarray, width: int) -> np.ndarray:
    return np.convolve(values, np.ones(width), "same")


def window_medians(
    values: np.ndarray, centres: np.ndarray, half: int, block: int = MEDIAN_BLOCK
) -> np.ndarray:
    """The median of values[c - half : c + half + 1] (cut at the ends) for each centre c.

    Windows are copied `block` samples at a time, so memory stays bounded on long recordings."""
    out = np.empty(len(centres))
    inner = (centres >= half) & (centres + half < len(values))
    if len(values) > 2 * half:
        windows = np.lib.stride_tricks.sliding_window_view(values, 2 * half + 1)
        starts = centres[inner] - half
        medians = np.empty(len(starts))
        rows = max(1, block // (2 * half + 1))
        for lo in range(0, len(starts), rows):
            medians[lo : lo + rows] = np.median(windows[starts[lo : lo + rows]], axis=1)
        out[inner] = medians
    for k in np.flatnonzero(~inner):  # the few windows the ends cut short
        c = centres[k]
        out[k] = np.median(values[max(0, c - half) : c + half + 1])
    return out


def envelope_breakpoints(x: np.ndarray, rate: float) -> tuple[Points, Points]:
    """Amplitude and normalised-frequency breakpoints of a waveform (fraction of full scale)."""
    # Beyond 1e100 times full scale the envelope is 1 all the same; clipped, the squares and
    # products below stay finite (a design with gains of 1e300 warned of overflow on stderr).
    x = np.clip(x, -1e100, 1e100)
    padded = np.concatenate([[0.0], x, [0.0]])
    neighbours = padded[2:] + padded[:-2]
    width = max(3, int(round(ANALYSIS_WINDOW * rate)))
    energy = _window_sum(2.0 * x * x, width)
    cos_w = np.clip(_window_sum(x * neighbours, width) / np.maximum(energy, 1e-300), -1.0, 1.0)
    omega = np.arccos(cos_w)  # radians per sample of the local carrier
    # Where the signal is too weak to carry a frequency, take it from the nearest strong parts.
    reliable = energy / width > (AMPLITUDE_TOLERANCE / 2) ** 2
    index = np.arange(len(x))
    if reliable.any():
        omega = np.interp(index, index[reliable], omega[reliable])
    else:
        omega = np.full(len(x), 2.0 * np.pi * carrier_hz(0.5) / rate)
    omega = np.clip(omega, np.pi * F_MIN / rate, min(4.0 * np.pi * F_MAX / rate, 0.9 * np.pi))
    quadrature = (padded[2:] - padded[:-2]) / (2.0 * np.maximum(np.sin(omega), 1e-6))
    envelope = np.sqrt(x * x + quadrature * quadrature)
    step = max(1, int(round(GRID * rate)))
    centres = np.arange(0, len(x), step)
    if centres[-1] != len(x) - 1:
        centres = np.append(centres, len(x) - 1)
    amp = window_medians(envelope, centres, step // 2)
    hz = omega[centres] * rate / (2.0 * np.pi)
    times = centres / rate
    return (
        simplify(times, np.clip(amp, 0.0, 1.0), AMPLITUDE_TOLERANCE),
        simplify(times, normalised_frequency(hz), FREQUENCY_TOLERANCE),
    )


def simplify(t: np.ndarray, v: np.ndarray, tolerance: float) -> Points:
    """Fewest breakpoints whose straight segments stay within tolerance of v (Douglas-Peucker)."""
    t = np.asarray(t, dtype=np.float64)
    v = np.asarray(v, dtype=np.float64)
    if len(t) < 3:
        return [(float(a), float(b)) for a, b in zip(t, v, strict=True)]
    keep = np.zeros(len(t), dtype=bool)
    keep[[0, -1]] = True
    stack = [(0, len(t) - 1)]
    while stack:
        i, j = stack.pop()
        if j - i < 2:
            continue
        inner = np.arange(i + 1, j)
        span = t[j] - t[i]
        if span > 0:
            line = v[i] + (v[j] - v[i]) * (t[inner] - t[i]) / span
        else:
            line = np.full(len(inner), v[i])
        errors = np.abs(v[inner] - line)
        worst = int(np.argmax(errors))
        if errors[worst] > tolerance:
            k = int(inner[worst])
            keep[k] = True
            stack += [(i, k), (k, j)]
    return [(float(t[k]), float(v[k])) for k in np.flatnonzero(keep)]


def trim_silence(points: Points) -> Points:
    """Drop leading and trailing breakpoints of a silent stretch, keeping the edge of the sound."""
    lo, hi = 0, len(points)
    while lo + 1 < hi and points[lo][1] == 0.0 and points[lo + 1][1] == 0.0:
        lo += 1
    while hi - 1 > lo + 1 and points[hi - 1][1] == 0.0 and points[hi - 2][1] == 0.0:
        hi -= 1
    return points[lo:hi]


def clip_points(points: Points, lo: float, hi: float) -> Points:
    """The breakpoints within [lo, hi], with values interpolated at lo and hi."""
    t = np.array([p[0] for p in points])
    v = np.array([p[1] for p in points])
    inner = [p for p in points if lo < p[0] < hi]
    ends = [(lo, float(np.interp(lo, t, v))), (hi, float(np.interp(hi, t, v)))]
    return [ends[0], *inner, ends[1]] if hi > lo else ends[:1]
