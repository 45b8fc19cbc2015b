"""Render one clip on an output grid: source mapping, stretch, reverse, amplitude and fades."""

from __future__ import annotations

import math

import numpy as np

from timeline.fades import fade_envelope
from timeline.model import Clip
from timeline.quality import QualityPreset
from timeline.tiles import Tile


def clip_sample_range(clip: Clip, t0: float, rate: float, n: int) -> tuple[int, int]:
    """Indices [i0, i1) of the grid t0 + i/rate (i < n) that fall inside the clip's [start, end)."""
    i0 = math.ceil((clip.start - t0) * rate - 1e-9)
    i1 = math.ceil((clip.end - t0) * rate - 1e-9)
    return max(i0, 0), min(max(i1, 0), n)


def render_clip(
    clip: Clip, tile: Tile, t_first: float, rate: float, n: int, quality: QualityPreset
) -> np.ndarray:
    """The clip's values in tile units at t_first + i/rate for i < n (all inside the clip)."""
    if n <= 0:
        return np.zeros(0)
    pos0 = t_first - clip.start  # offset of the first sample into the clip
    values = _source_values(clip, tile, pos0, 1.0 / rate, n, quality)
    # Overflow shows as inf, which the mixer reports as one clear error.
    with np.errstate(over="ignore", invalid="ignore"):
        if clip.scale != 1.0:
            values = values * clip.scale
        if clip.offset != 0.0:
            values = values + clip.offset
        if clip.gain != 1.0:
            values = values * clip.gain
        env = fade_envelope(pos0 + np.arange(n) / rate, clip.duration, clip.fade_in, clip.fade_out)
        if env is not None:
            values = values * env
    return values


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
