"""What a clip looks like at a zoom: per-pixel-column min/max of its values (Qt-free).

Tiles are summarised once into peak pyramids (sampled tiles from their samples, shapes from a
render at the project rate); a clip's stretch, reversal, amplitude and fades are then applied to
the column summaries, so drawing costs the same for a second or an hour.
"""

from __future__ import annotations

import math

import numpy as np

from timeline.model import Clip
from timeline.signal.fades import fade_envelope
from timeline.signal.render_presets import preset
from timeline.tiles import SampledTile, Tile

from .peaks import PeakPyramid, PyramidCache

MAX_SHAPE_SAMPLES = 2_000_000

_cache = PyramidCache()


def tile_samples(tile: Tile, rate: float) -> tuple[np.ndarray, float]:
    """Samples of a tile for display, and their rate."""
    if isinstance(tile, SampledTile):
        return tile.data, tile.rate
    rate = min(rate, MAX_SHAPE_SAMPLES / tile.duration)
    n = max(2, int(math.ceil(tile.duration * rate)) + 1)
    return tile.render(0.0, 1.0 / rate, n, preset("normal")), rate


def tile_pyramid(tile: Tile, rate: float) -> tuple[PeakPyramid, float]:
    """The cached peak pyramid of a tile, and the rate of its samples."""
    data_rate = (
        tile.rate if isinstance(tile, SampledTile) else min(rate, MAX_SHAPE_SAMPLES / tile.duration)
    )
    pyramid = _cache.get(f"{tile.key}@{data_rate}", lambda: tile_samples(tile, rate)[0])
    return pyramid, data_rate


def clip_columns(
    clip: Clip, tile: Tile, rate: float, t0: float, t1: float, count: int
) -> tuple[np.ndarray, np.ndarray]:
    """Min and max of the clip's values (tile units, gain and fades) in columns over [t0, t1)."""
    t0, t1 = max(t0, clip.start), min(t1, clip.end)
    count = max(1, int(count))
    if t1 <= t0:
        return np.zeros(count), np.zeros(count)
    pyramid, data_rate = tile_pyramid(tile, rate)
    pos = np.linspace(t0 - clip.start, t1 - clip.start, count + 1)
    if clip.stretch_mode == "squeeze":
        x = pos / clip.stretch
        lo, hi = _source_columns(clip, pyramid, data_rate, x[0], x[-1], count)
    else:
        length = clip.source_length
        width = (pos[1] - pos[0]) or length
        per_loop = max(1, int(math.ceil(length / width)))
        loop_lo, loop_hi = _source_columns(clip, pyramid, data_rate, 0.0, length, per_loop)
        at = np.fmod(pos[:-1] + clip.loop_phase, length)
        which = np.clip((at / length * per_loop).astype(np.int64), 0, per_loop - 1)
        lo, hi = loop_lo[which], loop_hi[which]
    lo = lo * clip.scale + clip.offset
    hi = hi * clip.scale + clip.offset
    lo, hi = np.minimum(lo, hi) * clip.gain, np.maximum(lo, hi) * clip.gain
    lo, hi = np.minimum(lo, hi), np.maximum(lo, hi)
    env = fade_envelope(0.5 * (pos[:-1] + pos[1:]), clip.duration, clip.fade_in, clip.fade_out)
    if env is not None:
        lo, hi = lo * env, hi * env
    return lo, hi


def _source_columns(
    clip: Clip, pyramid: PeakPyramid, data_rate: float, x0: float, x1: float, count: int
) -> tuple[np.ndarray, np.ndarray]:
    """Column min/max over source offsets [x0, x1) from the clip's source start (or end)."""
    if clip.reverse:
        a, b = clip.source_out - x1, clip.source_out - x0
    else:
        a, b = clip.source_in + x0, clip.source_in + x1
    lo, hi = pyramid.columns(a * data_rate, b * data_rate, count)
    if clip.reverse:
        lo, hi = lo[::-1], hi[::-1]
    return lo.astype(np.float64), hi.astype(np.float64)
