"""Render one clip on an output grid: source mapping, stretch, reverse, amplitude and fades."""

from __future__ import annotations

import math

import numpy as np

from timeline.model import Clip, Fade
from timeline.signal.fades import fade_envelope
from timeline.signal.grid_shapes import fade_on_grid
from timeline.signal.render_presets import QualityPreset
from timeline.tiles import Tile

NO_FADE = Fade()


# A float time meant on the sample grid lands within this many of its operands' magnitude (in
# samples) of the grid point: each of the few roundings (the decimal start, start + duration, the
# product with the rate) errs by at most 2**-53 of its operands, so 2**-48 leaves room for a
# few more edits' sums and still never moves an off-grid clip by a visible amount (at 3600 s and
# 192 kHz it is 2.5e-6 samples).
GRID_TOLERANCE = 2.0**-48
MIN_TOLERANCE = 1e-9  # samples: the tolerance of short projects, as before


def on_grid(time: float, origin: float, rate: float) -> int | None:
    """The k with origin + k/rate == time up to the float error of (time - origin) * rate."""
    x = (time - origin) * rate
    k = round(x)
    tolerance = max(MIN_TOLERANCE, GRID_TOLERANCE * (abs(time) + abs(origin)) * rate)
    return k if abs(x - k) <= tolerance else None


def first_sample(time: float, origin: float, rate: float) -> int:
    """The first k of the grid origin + k/rate at or after `time` (exact on the grid)."""
    k = on_grid(time, origin, rate)
    return math.ceil((time - origin) * rate) if k is None else k


_FAR = float(2**62)  # samples: a clip's end beyond this is placed here (clip_samples)


def clip_samples(clip: Clip, origin: float, rate: float) -> tuple[int, int, float]:
    """The clip's samples [c0, c1) on the grid origin + k/rate, and the clip offset of c0.

    The offset (the sub-sample phase of the clip's first sample) is exactly 0 for a clip on the
    grid, so chunked and whole renders place and evaluate it alike. (first_sample for both
    ends, written out: the mixer places every clip with it.)
    """
    start, end = clip.start, clip.end
    # an end past 2^62 samples (a stretch of 1e308 is 1e311) lies beyond any render all the same
    x = min(max((start - origin) * rate, -_FAR), _FAR)
    y = min(max((end - origin) * rate, -_FAR), _FAR)
    c0, c1 = round(x), round(y)
    scale = GRID_TOLERANCE * rate
    if abs(y - c1) > max(MIN_TOLERANCE, scale * (abs(end) + abs(origin))):
        c1 = math.ceil(y)
    if abs(x - c0) <= max(MIN_TOLERANCE, scale * (abs(start) + abs(origin))):
        return c0, c1, 0.0
    c0 = math.ceil(x)
    return c0, c1, (origin + c0 / rate) - start


def clip_sample_range(clip: Clip, t0: float, rate: float, n: int) -> tuple[int, int]:
    """Indices [i0, i1) of the grid t0 + i/rate (i < n) that fall inside the clip's [start, end)."""
    c0, c1, _ = clip_samples(clip, t0, rate)
    return max(c0, 0), min(max(c1, 0), n)


def render_clip(
    clip: Clip, tile: Tile, t_first: float, rate: float, n: int, quality: QualityPreset
) -> np.ndarray:
    """The clip's values in tile units at t_first + i/rate for i < n (all inside the clip)."""
    return render_shape(clip, tile, t_first - clip.start, rate, n, quality, clip.gain)


def render_shape(
    clip: Clip,
    tile: Tile,
    pos0: float,
    rate: float,
    n: int,
    quality: QualityPreset,
    gain: float = 1.0,
) -> np.ndarray:
    """The clip's values times gain at offsets pos0 + i/rate into the clip (its start ignored).

    The mixer renders shapes with gain 1 and weights them when it adds them.
    """
    if n <= 0:
        return np.zeros(0)
    values = _source_values(clip, tile, pos0, 1.0 / rate, n, quality)
    if not values.flags.writeable:
        values = values.copy()
    # Overflow shows as inf, which the mixer reports as one clear error.
    with np.errstate(over="ignore", invalid="ignore"):
        if clip.scale != 1.0:
            values *= clip.scale
        if clip.offset != 0.0:
            values += clip.offset
        if gain != 1.0:
            values *= gain
        _apply_fades(values, clip, pos0, rate)
    return values


def _apply_fades(values: np.ndarray, clip: Clip, pos0: float, rate: float) -> None:
    """Multiply by the fade gains where they are not exactly 1 (the fade spans, plus a sample).

    Past a fade's span its gain is exactly 1.0 for every shape, so leaving those samples alone
    gives the same bits as multiplying the whole clip, at the cost of the fades alone.
    """
    fade_in, fade_out = clip.fade_in, clip.fade_out
    if fade_in.length <= 0 and fade_out.length <= 0:
        return
    n = len(values)
    a = min(n, max(0, math.ceil((fade_in.length - pos0) * rate) + 1)) if fade_in.length > 0 else 0
    z = n
    if fade_out.length > 0:
        z = min(n, max(0, math.floor((clip.duration - fade_out.length - pos0) * rate) - 1))
    spans = [(0, n)] if z <= a else [(0, a), (z, n)]
    for lo, hi in spans:
        if hi > lo:
            first, last = pos0 + lo / rate, pos0 + (hi - 1) / rate  # pos[0], pos[-1] below
            # a fade whose gain is exactly 1 over the whole span (its x >= 1 at the span's end
            # nearest it: x is monotone in pos) is left out, with the same bits
            fi = fade_in if fade_in.length > 0 and first / fade_in.length < 1.0 else NO_FADE
            ends = clip.duration - last
            fo = fade_out if fade_out.length > 0 and ends / fade_out.length < 1.0 else NO_FADE
            if fi.length > 0 or fo.length > 0:
                _fade(values, lo, hi, pos0, rate, clip.duration, fi, fo)


def _fade(values: np.ndarray, lo: int, hi: int, pos0: float, rate: float, duration: float,
          fade_in: Fade, fade_out: Fade) -> None:  # fmt: skip
    """values[lo:hi] *= the fades' gains at offsets pos0 + k/rate: the compiled loop where it
    applies (timeline.signal.grid_shapes, the same bits), else numpy."""
    fi = (fade_in.length, fade_in.shape) if fade_in.length > 0 else None
    fo = (fade_out.length, fade_out.shape) if fade_out.length > 0 else None
    if not fade_on_grid(values, lo, hi, pos0, rate, duration, fi, fo):
        pos = pos0 + np.arange(lo, hi) / rate
        values[lo:hi] *= fade_envelope(pos, duration, fade_in, fade_out)


def _source_values(
    clip: Clip, tile: Tile, pos0: float, dt: float, n: int, quality: QualityPreset
) -> np.ndarray:
    """Tile values for clip offsets pos0 + i*dt, following stretch mode and reversal."""
    if clip.stretch_mode == "squeeze":
        return _mapped(clip, tile, pos0 / clip.stretch, dt / clip.stretch, n, quality)
    # repeat: the source loops at its own speed; render each pass through the loop separately.
    length = clip.source_length
    out = np.empty(n)
    i = 0
    while i < n:
        x = math.fmod(pos0 + i * dt + clip.loop_phase, length)
        remaining = math.ceil((length - x) / dt - 1e-9)
        count = max(1, min(n - i, remaining))
        out[i : i + count] = _mapped(clip, tile, x, dt, count, quality)
        i += count
    return out


def _mapped(
    clip: Clip, tile: Tile, x0: float, dx: float, n: int, quality: QualityPreset
) -> np.ndarray:
    """Tile values at source offsets x0 + i*dx from source_in (mirrored when reversed)."""
    if clip.reverse:
        u0 = clip.source_out - tile.reverse_shift - x0
        return tile.render(u0, -dx, n, quality)
    return tile.render(clip.source_in + x0, dx, n, quality)
