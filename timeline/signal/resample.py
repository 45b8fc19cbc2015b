"""Sampled-signal evaluation on an arithmetic grid: direct, linear, or band-limited (soxr)."""

from __future__ import annotations

import math
import threading
from collections import OrderedDict
from fractions import Fraction
from functools import cache

import numpy as np

from timeline.signal import compiled, samples
from timeline.signal.render_presets import QualityPreset

# Samples of context kept either side of a segment so soxr's filter settles before the part used.
_SOXR_MARGIN = 256
_SINC_HALF = 32  # taps either side of a fractional-delay filter
_SINC_BETA = 9.0  # its Kaiser window: about -90 dB side lobes
# A recording whose resampled whole is at most this many samples is resampled whole once per
# (step, quality) and kept; its clips are read from that (longer ones are resampled clip by clip).
WHOLE_SAMPLES = 2**20
# soxr's margins become _SOXR_MARGIN / step output samples each when upsampling; past this many
# (a recording at 0.005 Hz rendered at 10 kHz: 5e8), the wanted samples are summed directly
# from the source by a windowed sinc instead, so the work follows the output, not the ratio.
_MAX_MARGIN_OUTPUT = 2**20
# Downsampling by more source samples per output sample than this (a 1e12 Hz table played at
# 10 Hz) is a box average: soxr designs a filter as long as the ratio (0.1 s at 2^12, 1.4 s at
# 2^16, 52 s for 1e6 under load: a 100-sample AIFF at 1e9 Hz rendered at 1 kHz), and a source
# sampled 4096 times faster than the output holds little a box average would keep wrongly.
_MAX_SOXR_STEP = 2**12
_SINC_PHASES = 2**12  # the sinc table's points per source sample
_KNOT_ROWS = 256  # source samples whose knots (_SINC_PHASES each) one pass of the direct sinc sums
_UPSAMPLE_CHUNK = 2**18  # and at most this many outputs per pass
_WHOLE_BYTES = 64 * 2**20  # resampled recordings kept, least recently used dropped first


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
    if quality.resampler == "linear":
        return _interpolate(data, start + step * np.arange(n), quality.interpolation)
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
    # float64 arithmetic whatever the stored precision (a float32 recording's values are exact)
    p0 = data[np.clip(i - 1, 0, n - 1)].astype(np.float64, copy=False)
    p1 = data[i].astype(np.float64, copy=False)
    p2 = data[i + 1].astype(np.float64, copy=False)
    p3 = data[np.clip(i + 2, 0, n - 1)].astype(np.float64, copy=False)
    return p1 + 0.5 * t * (
        p2 - p0 + t * (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3 + t * (3.0 * (p1 - p2) + p3 - p0))
    )


def _aligned_start(start: float, step: float) -> int | None:
    """A whole source index lo, at least _SOXR_MARGIN before start, that lies a whole number of
    output steps before it (lo = start - M*step), or None when no such index exists nearby.

    Resampling from there puts every wanted output sample exactly on a resampled one, so no
    interpolation is needed after soxr. Clips on the project grid always have one.
    """
    q = Fraction(step).limit_denominator(4096).denominator
    first = math.ceil(_SOXR_MARGIN / step)
    m = first + np.arange(q)
    lo = start - m * step
    hit = np.flatnonzero(np.abs(lo - np.round(lo)) < 1e-6)
    return round(float(lo[hit[0]])) if hit.size else None


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
    if _SOXR_MARGIN / step > max(_MAX_MARGIN_OUTPUT, n):
        out = _sinc_upsample(data, start, step, n)
        return out[::-1] if reverse else out
    if step > _MAX_SOXR_STEP:
        out = _box_average(data, start, step, n)
        return out[::-1] if reverse else out
    soxr_quality = "VHQ" if quality.resampler == "soxr-vhq" else "HQ"
    whole = _whole(data, step, soxr_quality)
    if whole is not None:
        lo, resampled = whole
        aligned = None
    else:
        aligned = _aligned_start(start, step)
        lo = aligned if aligned is not None else int(np.floor(start)) - _SOXR_MARGIN
        hi = int(np.ceil(start + step * (n - 1))) + _SOXR_MARGIN + 1
        segment = _take(data, lo, hi - lo)
        resampled = soxr.resample(segment, 1.0, 1.0 / step, quality=soxr_quality)
    # resampled[j] sits at source index lo + j*step; the wanted samples at offset + i.
    offset = (start - lo) / step
    nearest = round(offset)
    if aligned is not None or abs(offset - nearest) < 1e-9:
        out = _take(resampled, nearest, n)
    else:
        first = math.floor(offset)
        out = _fractional_delay(resampled, first, offset - first, n)
    return out[::-1] if reverse else out


def _box_average(data: np.ndarray, start: float, step: float, n: int) -> np.ndarray:
    """Output i: the source samples nearest to it (within half a step) summed over the step."""
    out = np.zeros(n)
    index = np.round((np.arange(len(data)) - start) / step)
    inside = (index >= 0) & (index < n)
    np.add.at(out, index[inside].astype(np.int64), data[inside] / step)
    return out


_kept: OrderedDict[tuple[int, float, str], tuple[np.ndarray, int, np.ndarray]] = OrderedDict()
_kept_bytes = 0
_kept_lock = threading.Lock()


def _whole(data: np.ndarray, step: float, soxr_quality: str) -> tuple[int, np.ndarray] | None:
    """(lo, the whole recording resampled from source index lo on), kept for its next clips, or
    None for a recording that is long or that its owner may still change.

    lo lies a whole number of output steps before source index 0, so clips on the project grid
    (source offsets on the output grid) read resampled samples exactly. One resampling of the
    whole recording (zeros around it) also puts every clip away from the resampler's start and
    end transients, which a segment cut out per clip had within its margin.
    """
    if len(data) / step > WHOLE_SAMPLES or not samples.frozen(data):
        return None
    global _kept_bytes
    key = (id(data), step, soxr_quality)
    with _kept_lock:
        kept = _kept.get(key)
        if kept is not None and kept[0] is data:
            _kept.move_to_end(key)
            return kept[1], kept[2]
    import soxr

    lo = _aligned_start(0.0, step)
    lo = -_SOXR_MARGIN if lo is None else lo
    hi = len(data) + _SOXR_MARGIN + 1
    resampled = soxr.resample(_take(data, lo, hi - lo), 1.0, 1.0 / step, quality=soxr_quality)
    resampled.setflags(write=False)
    with _kept_lock:
        old = _kept.pop(key, None)
        _kept_bytes -= 0 if old is None else old[2].nbytes
        _kept[key] = (data, lo, resampled)  # the data kept too, so its id is not reused
        _kept_bytes += resampled.nbytes
        while _kept_bytes > _WHOLE_BYTES and len(_kept) > 1:
            _, (_, _, dropped) = _kept.popitem(last=False)
            _kept_bytes -= dropped.nbytes
    return lo, resampled


def forget_resampled() -> None:
    """Drop the kept resampled recordings (a benchmark's render from scratch, a test)."""
    global _kept_bytes
    with _kept_lock:
        _kept.clear()
        _kept_bytes = 0


def _sinc_upsample(data: np.ndarray, start: float, step: float, n: int) -> np.ndarray:
    """data band-limited to its own Nyquist frequency at source indices start + i*step (step
    well below 1), by the Kaiser-windowed sinc of _SINC_HALF taps either side, tabulated.

    The taps are the table interpolated linearly, and the table's points lie _SINC_PHASES to a
    source sample, so the sum is a piecewise-linear function of the position with its knots on
    that grid: the knots the outputs fall between are summed once (64 products each, one matrix
    product over the source samples' windows) and the outputs interpolated between them. Fewer
    knots than outputs when upsampling by more than _SINC_PHASES (every call from _band_limited),
    so the work is about one interpolation per output, whatever the ratio.
    """
    out = np.zeros(n)
    # only outputs within the filter's reach of the samples can be non-zero
    first = max(0, math.ceil((-_SINC_HALF - start) / step))
    last = min(n, math.floor((len(data) - 1 + _SINC_HALF - start) / step) + 1)
    # outputs per pass: at most _UPSAMPLE_CHUNK, spanning at most _KNOT_ROWS source samples
    chunk = max(1, int(min(_UPSAMPLE_CHUNK, _KNOT_ROWS / step)))
    for lo in range(first, last, chunk):
        x = np.arange(lo, min(lo + chunk, last), dtype=np.float64)
        x *= step
        x += start  # start + step * i, as numpy's two roundings
        out[lo : lo + len(x)] = _between_knots(data, x)
    return out


def _between_knots(data: np.ndarray, x: np.ndarray) -> np.ndarray:
    """The windowed-sinc sum at ascending source positions x, interpolated between its knots."""
    row0 = math.floor(x[0])
    rows = math.floor(x[-1]) + 2 - row0  # the last output's right knot starts the row after
    # window[r, j] = data[row0 + r - _SINC_HALF + 1 + j], zero outside the data
    span = _take(data, row0 - _SINC_HALF + 1, rows + 2 * _SINC_HALF - 1).astype(np.float64)
    window = np.lib.stride_tricks.sliding_window_view(span, 2 * _SINC_HALF).copy()  # for BLAS
    # knots[r * _SINC_PHASES + m]: the sum at source position row0 + r + m / _SINC_PHASES
    knots = (window @ _sinc_phases()).ravel()
    at = row0 + np.arange(knots.size) / _SINC_PHASES  # exact: a power of two
    return np.interp(x, at, knots)


@cache
def _sinc_phases() -> np.ndarray:
    """The windowed sinc (Kaiser, beta _SINC_BETA, over +-_SINC_HALF) tabulated _SINC_PHASES
    times a sample for linear interpolation (within 1e-7 of the exact taps), as a matrix: for
    knots m / _SINC_PHASES past a whole source index b, row j, column m holds the tap of sample
    b - _SINC_HALF + 1 + j, at the distance _SINC_HALF - 1 - j + m / _SINC_PHASES."""
    d = np.arange(-_SINC_HALF * _SINC_PHASES, _SINC_HALF * _SINC_PHASES) / _SINC_PHASES
    r = d / _SINC_HALF
    window = np.i0(_SINC_BETA * np.sqrt(np.clip(1.0 - r * r, 0.0, None))) / np.i0(_SINC_BETA)
    table = np.sinc(d) * window  # from -_SINC_HALF up to (not at) _SINC_HALF
    phases = np.ascontiguousarray(table.reshape(2 * _SINC_HALF, _SINC_PHASES)[::-1])
    phases.setflags(write=False)
    return phases


@cache
def _kaiser() -> np.ndarray:
    """The sinc filter's window (the same every call: computed once)."""
    window = np.kaiser(2 * _SINC_HALF, _SINC_BETA)
    window.setflags(write=False)
    return window


def _fractional_delay(x: np.ndarray, first: int, fraction: float, n: int) -> np.ndarray:
    """x at indices first + fraction + i (i < n) by a Kaiser-windowed sinc (band-limited x)."""
    k = np.arange(-_SINC_HALF + 1, _SINC_HALF + 1)
    taps = np.sinc(k - fraction) * _kaiser()
    taps /= taps.sum()
    span = _take(x, first - _SINC_HALF, n + 2 * _SINC_HALF)
    if compiled.compiled_wanted(n) and _compiled_delay_matches():
        from timeline.signal.render_kernels import fractional_delay

        out = np.empty(n)
        fractional_delay(span, taps, out)  # numpy's bits, ~3x faster
        return out
    # out[i] = sum_k taps[k] * x[first + i + k]
    return np.convolve(span, taps[::-1], mode="valid")[1 : n + 1]


@cache
def _compiled_delay_matches() -> bool:
    """True when the compiled delay gives np.convolve's bits on this machine (its loop sums as
    OpenBLAS's ddot kernel for AVX2 does; another BLAS or kernel may sum otherwise)."""
    from timeline.signal.render_kernels import fractional_delay

    rng = np.random.default_rng(0)
    span = rng.standard_normal(3 * 256 + 2 * _SINC_HALF + 5)
    taps = rng.standard_normal(2 * _SINC_HALF)
    n = span.size - 2 * _SINC_HALF
    out = np.empty(n)
    fractional_delay(span, taps, out)
    return bool(np.array_equal(out, np.convolve(span, taps[::-1], mode="valid")[1 : n + 1]))
