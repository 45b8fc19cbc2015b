"""Emphasis: the hits that start a sound's events, found from the sound's own onset statistics.

By default (`adaptive`) an emphasis goes where the onset strength (the summed rise of each
frequency bin's log-compressed magnitude since the previous spectrum frame, spectrum.py) has a
local maximum (within +-`LOCAL_MAXIMUM` s) that stands out of the sound around it: above the
median of the onset strength over +-`CONTEXT` s by `spread` times its median absolute deviation
there, above a floor that is a share of the sound's strongest onset, and where the frame power
rises by at least `RISE_DB` across the onset (a transient, not a wobble of a steady sound) to
within `GATE_DB` of the sound's loudest frame (not a hiss between the sound's events). Both
the spread and the floor fall as `sensitivity` rises, so the control spans from the sound's
strongest hit alone (near 0 %) to every transient that stands out of its surroundings (100 %);
between, how many hits a second depends on the sound itself: a rattle gets many, a single
explosion one. Of hits closer than `hit_gap` (`peak_window` at 100 %, up to a second near 0 %)
the stronger stays. Nothing here was fitted to
reference designs: the constants below are set on synthetic click trains and bursts (tests).

Each hit is placed on the highest amplitude breakpoint from `SNAP_BEFORE` before the onset frame's
centre to `SNAP_AFTER` and half a frame after it (a frame sees an attack before its centre
reaches it; a breakpoint is added at the onset when the reduced envelope has none there), and a
breakpoint is added one `update` after it when the next is further, so that ducking dips the
envelope at the hit and not along a whole reduced segment.

Without `adaptive`, Meta Haptics Studio's peak picking: a breakpoint of the reduced amplitude
envelope is a peak when it rises more than `minimum_rise` above the breakpoint before it, the
next does not keep rising by more than `plateau` % of that rise, and it comes at least
`peak_window` after the last peak; `sensitivity` keeps the peaks whose spectral flux is in that
top part of the range between the weakest and strongest.

Either way an emphasis takes its breakpoint's amplitude, a frequency mapping its spectral flux
into sharpness_min..sharpness_max among the hits found, and the envelope under it is ducked by
`ducking` % so the emphasis stands out.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from timeline.analysis.settings import AnalysisSettings
from timeline.analysis.spectrum import Features

CONTEXT = 0.25  # s either side over which the local median and deviation are taken
LOCAL_MAXIMUM = 0.015  # s either side within which an onset's strength is the largest
SPREAD = (1.0, 24.0)  # deviations above the local median at 100 % and 0 % sensitivity
FLOOR = (0.05, 1.0)  # share of the strongest onset at 100 % and 0 % sensitivity
GAP_MAX = 1.0  # s: least time between hits near 0 % sensitivity (peak_window at 100 %)
RISE_DB = 1.0  # least rise of frame power across an onset (dB)
GATE_DB = -40.0  # least frame power after an onset, relative to the sound's loudest frame (dB)
RISE_SPAN = 0.02  # s: power compared this far before and after the onset frame
SNAP_BEFORE = 0.005  # s: an emphasis goes on the highest breakpoint from this before the onset
SNAP_AFTER = 0.02  # s: ... to this and half a spectrum frame after it
CHUNK = 1 << 16  # frames whose onset statistics are taken at once (bounded working memory)


@dataclass(frozen=True)
class Frames:
    """The spectrum frames' times (s, their centres) and onset features."""

    times: np.ndarray
    features: Features


def peak_indices(t: np.ndarray, a: np.ndarray, settings: AnalysisSettings) -> np.ndarray:
    """Indices of the amplitude breakpoints that are peaks (Meta's picking, module docstring)."""
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


def _sensitivity_scale(settings: AnalysisSettings) -> float:
    """(1 - sensitivity)^2: how strict the adaptive threshold is (1 at 0 %, 0 at 100 %)."""
    return (1.0 - settings.sensitivity / 100.0) ** 2


def _frames(seconds: float, times: np.ndarray) -> int:
    hop = float(times[1] - times[0]) if len(times) > 1 else seconds
    return max(1, round(seconds / hop))


def onset_frames(frames: Frames, settings: AnalysisSettings) -> np.ndarray:
    """Indices of the frames that hold an onset (the adaptive method, module docstring).

    The local statistics are taken CHUNK frames at a time, each chunk with the margin its
    filters reach, so hours of frames need a chunk's worth of working memory (the result is
    the same as over all frames at once)."""
    times, strength = frames.times, frames.features.strength
    if len(strength) < 3 or settings.sensitivity <= 0 or float(strength.max()) <= 0:
        return np.empty(0, dtype=np.intp)
    strict = _sensitivity_scale(settings)
    spread = SPREAD[0] + strict * (SPREAD[1] - SPREAD[0])
    floor = (FLOOR[0] + strict * (FLOOR[1] - FLOOR[0])) * float(strength.max())
    sizes = _Sizes(
        2 * _frames(CONTEXT, times) + 1, 2 * _frames(LOCAL_MAXIMUM, times) + 1,
        _frames(RISE_SPAN, times),
    )  # fmt: skip
    gate = (float(frames.features.power.astype(np.float64).max()) + 1e-20) * 10.0 ** (
        GATE_DB / 10.0
    )
    margin = 2 * sizes.context + sizes.local + 2 * sizes.span
    found = [
        start + _onsets_in(frames.features, lo, hi, start - lo, end - lo, spread, floor, gate,
                           sizes)
        for start in range(0, len(strength), CHUNK)
        for end, lo, hi in [(min(start + CHUNK, len(strength)), max(0, start - margin),
                             min(len(strength), start + CHUNK + margin))]
    ]  # fmt: skip
    index = np.concatenate(found)
    score = strength[index].astype(np.float64)
    return _spaced(index, score, times[index], hit_gap(settings))


@dataclass(frozen=True)
class _Sizes:
    """Frames the onset statistics reach: the context's and local maximum's windows, the span
    of the power's rise."""

    context: int
    local: int
    span: int


def _onsets_in(
    features: Features,
    lo: int,
    hi: int,
    first: int,
    last: int,
    spread: float,
    floor: float,
    gate: float,
    sizes: _Sizes,
) -> np.ndarray:
    """The onsets among frames first..last of frames lo..hi (which hold the margins the filters
    reach), counted from first."""
    from scipy.ndimage import maximum_filter1d, median_filter

    strength = features.strength[lo:hi].astype(np.float64)
    median = median_filter(strength, size=sizes.context, mode="nearest")
    deviation = median_filter(np.abs(strength - median), size=sizes.context, mode="nearest")
    threshold = np.maximum(median + spread * deviation, floor)
    local = maximum_filter1d(strength, sizes.local, mode="nearest")
    power = features.power[lo:hi].astype(np.float64) + 1e-20
    span = sizes.span
    before = power[np.maximum(np.arange(len(power)) - span, 0)]
    after = maximum_filter1d(power, span + 1, origin=-(span // 2), mode="nearest")
    rises = 10.0 * np.log10(after / before) >= RISE_DB
    rises &= after >= gate
    keep = (strength >= local) & (strength > threshold) & rises
    return np.flatnonzero(keep[first:last])


def hit_gap(settings: AnalysisSettings) -> float:
    """Least time between two hits: `peak_window` at 100 % sensitivity, rising towards GAP_MAX
    as it falls (geometrically, in the square of `_sensitivity_scale`), so that on dense, even
    material the density falls smoothly with the sensitivity."""
    low = max(settings.peak_window, 1e-3)
    return low * (max(GAP_MAX, low) / low) ** (_sensitivity_scale(settings) ** 2)


def _spaced(index: np.ndarray, score: np.ndarray, times: np.ndarray, gap: float) -> np.ndarray:
    """The indices kept when, of any two closer than `gap` seconds, only the stronger stays."""
    kept: list[int] = []
    taken: list[float] = []
    for k in np.argsort(-score, kind="stable"):
        if all(abs(times[k] - s) >= gap for s in taken):
            kept.append(int(index[k]))
            taken.append(float(times[k]))
    return np.array(sorted(kept), dtype=np.intp)


def _snap(
    t: np.ndarray, a: np.ndarray, onsets: np.ndarray, after: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(t, a, indices): each onset on its highest breakpoint from SNAP_BEFORE before it to
    `after` after it; a breakpoint is added at the onset where there is none."""
    onsets = np.clip(onsets, t[0], t[-1])
    lows, highs = onsets - SNAP_BEFORE, onsets + after
    empty = np.searchsorted(t, lows, "left") == np.searchsorted(t, highs, "right")
    if np.any(empty):
        t, a = _insert(t, a, onsets[empty])
    starts, ends = np.searchsorted(t, lows, "left"), np.searchsorted(t, highs, "right")
    peaks = [s + int(np.argmax(a[s:e])) for s, e in zip(starts, ends, strict=True)]
    return t, a, np.unique(np.array(peaks, dtype=np.intp))


def _insert(t: np.ndarray, a: np.ndarray, at: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    new = np.setdiff1d(at, t)
    values = np.interp(new, t, a)
    order = np.argsort(np.concatenate([t, new]), kind="stable")
    return np.concatenate([t, new])[order], np.concatenate([a, values])[order]


def emphasis(
    t: np.ndarray, a: np.ndarray, frames: Frames, rate: float, settings: AnalysisSettings
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(t, a, indices, amplitudes, frequencies): the amplitude breakpoints (with any added for
    an emphasis, the emphasised ones ducked), the emphasised indices and each one's values."""
    none = np.empty(0, dtype=np.intp), np.empty(0), np.empty(0)
    if not settings.emphasis or settings.sensitivity <= 0 or len(frames.times) == 0:
        return t, a, *none
    if settings.adaptive:
        onsets = frames.times[onset_frames(frames, settings)]
        if len(onsets) == 0:
            return t, a, *none
        half_frame = settings.fft_size / 2 / rate
        t, a, peaks = _snap(t, a, onsets, SNAP_AFTER + half_frame)
        score = _flux_at(t[peaks], frames)
        lo, hi = float(score.min()), float(score.max())
    else:
        peaks = peak_indices(t, a, settings)
        if len(peaks) == 0:
            return t, a, *none
        score = _flux_at(t[peaks], frames)
        lo, hi = float(score.min()), float(score.max())
        top = hi + (hi - lo) * 1e-3
        chosen = score >= top + settings.sensitivity / 100.0 * (lo - top)
        peaks, score = peaks[chosen], score[chosen]
    relative = (score - lo) / (hi - lo) if hi > lo else np.full(len(score), 0.5)
    freq = settings.sharpness_min + relative * (settings.sharpness_max - settings.sharpness_min)
    if settings.adaptive:
        t, a, peaks = _undipped_after(t, a, peaks, settings.update)
    else:
        a = a.copy()
    amp = a[peaks].copy()
    a[peaks] *= 1.0 - settings.ducking / 100.0
    return t, a, peaks, amp, freq


def _flux_at(when: np.ndarray, frames: Frames) -> np.ndarray:
    """The spectral flux at times `when`, straight between frames (np.interp), reading only the
    frames either side of each (no float64 copy of hours of frames)."""
    times, flux = frames.times, frames.features.flux
    if len(times) < 2:
        return np.interp(when, times, flux.astype(np.float64))
    j = np.clip(np.searchsorted(times, when, side="right"), 1, len(times) - 1)
    near = np.unique(np.concatenate([j - 1, j]))
    return np.interp(when, times[near], flux[near].astype(np.float64))


def _undipped_after(
    t: np.ndarray, a: np.ndarray, peaks: np.ndarray, update: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(t, a, peaks) with a breakpoint one `update` after each peak whose next one is further
    away, so ducking the peak dips the envelope there and not along a whole reduced segment."""
    times = t[peaks]
    following = np.append(t, np.inf)[peaks + 1]
    lonely = (following - times > 1.5 * update) & (times + update < t[-1])
    if lonely.any():
        t, a = _insert(t, a, times[lonely] + update)
    else:
        a = a.copy()
    return t, a, np.searchsorted(t, times)
