"""The evaluation floor of a full render: each clip sample evaluated once, without per-clip work.

A render must at least evaluate every sample its clips hold at full accuracy and add it once.
This module times the first part with the functions the mixer itself calls, but with the
positions of all clips that read one tile at one spacing gathered into one array beforehand, so
each function runs once per (tile, spacing) instead of once per clip:

* generators: `band_limited` on the tile's own function (np.sin for sines, the chirp's phase, the
  Fourier sum of a band-limited square, ...);
* splines: the curve's pieces over the sorted positions;
* recordings: soxr once per (tile, step) over the whole recording, then the 64-tap fractional
  delay over every sample of the clips that start off the resampled grid (what each clip needs
  on top of a shared resampling), or linear/cubic interpolation with the draft preset;
* fades: the fade gain over every sample inside a fade.

What is left out is the per-clip bookkeeping: placing clips, building each grid, scaling, the
per-call overhead of numpy and soxr on every clip, and the add (the memory pass measures that).
"""

from __future__ import annotations

import math
from collections import defaultdict
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from timeline.model import Clip, Project
from timeline.rendering.clip_render import clip_sample_range
from timeline.signal.band_limit import band_limited
from timeline.signal.fades import fade_in_gain
from timeline.signal.render_presets import QualityPreset, preset
from timeline.signal.resample import _SOXR_MARGIN, _aligned_start, _fractional_delay, _interpolate
from timeline.tiles import GeneratorTile, SampledTile, SplineTile, Tile


@dataclass(frozen=True)
class Work:
    """One batched evaluation of a tile (or of fades) for all the clips that need it."""

    label: str
    run: Callable[[], np.ndarray]


def _source_positions(clip: Clip, tile: Tile, pos: np.ndarray) -> tuple[np.ndarray, float]:
    """Tile positions of clip offsets `pos` (as clip_render maps them) and their spacing."""
    if clip.stretch_mode == "squeeze":
        x = pos / clip.stretch
    else:
        x = np.fmod(pos + clip.loop_phase, clip.source_length)
    if clip.reverse:
        return clip.source_out - tile.reverse_shift - x, -1.0 / clip.stretch
    return clip.source_in + x, 1.0 / clip.stretch


def _needs_delay(start: float, step: float, count: int) -> bool:
    """True when a clip starts between the samples of its recording resampled whole (as
    resample._band_limited decides), so it takes the fractional delay."""
    if step < 0:
        start, step = start + step * (count - 1), -step
    lo = _aligned_start(0.0, step)
    offset = (start - (-_SOXR_MARGIN if lo is None else lo)) / step
    return abs(offset - round(offset)) >= 1e-9


def _recording_work(tile: SampledTile, step: float, starts: list[tuple[float, int]],
                    quality: QualityPreset) -> list[Work]:  # fmt: skip
    """Resampling a recording once at `step`, and the per-sample delay its clips need."""
    if quality.resampler == "linear":
        index = np.concatenate([s + step * np.arange(c) for s, c in starts])
        method = quality.interpolation
        return [Work(f"{tile.name} interpolated", lambda: _interpolate(tile.data, index, method))]
    import soxr

    soxr_quality = "VHQ" if quality.resampler == "soxr-vhq" else "HQ"
    padded = np.concatenate([np.zeros(_SOXR_MARGIN), tile.data, np.zeros(_SOXR_MARGIN)])
    rate = 1.0 / abs(step)
    works = [Work(f"{tile.name} resampled",
                  lambda: soxr.resample(padded, 1.0, rate, quality=soxr_quality))]  # fmt: skip
    delayed = sum(c for s, c in starts if _needs_delay(s, step, c))
    if delayed:
        resampled = soxr.resample(padded, 1.0, rate, quality=soxr_quality)
        signal = np.resize(resampled, delayed + 128)  # as many samples as the clips hold
        works.append(Work(f"{tile.name} delayed",
                          lambda: _fractional_delay(signal, 40, 0.37, delayed)))  # fmt: skip
    return works


def evaluation_work(project: Project, start: float, stop: float,
                    quality: str | QualityPreset = "normal") -> list[Work]:  # fmt: skip
    """The batched evaluations that a render of the project's tracks on [start, stop) needs."""
    q = preset(quality)
    rate = float(project.rate)
    n = int(round((stop - start) * rate))
    positions: dict[tuple[str, float], list[np.ndarray]] = defaultdict(list)
    recordings: dict[tuple[str, float], list[tuple[float, int]]] = defaultdict(list)
    fades: dict[str, list[np.ndarray]] = defaultdict(list)
    works: list[Work] = []
    for track in project.tracks:
        for clip in track.clips:
            i0, i1 = clip_sample_range(clip, start, rate, n)
            if i1 <= i0:
                continue
            tile = project.tile(clip.tile_id)
            pos = start + np.arange(i0, i1) / rate - clip.start
            u, spacing = _source_positions(clip, tile, pos)
            du = spacing / rate
            if isinstance(tile, SampledTile):
                step = du * tile.rate
                first = float(u[0]) * tile.rate
                if not (abs(step) == 1.0 and first == math.floor(first)):  # else copied exactly
                    recordings[(clip.tile_id, step)].append((first, i1 - i0))
            elif isinstance(tile, GeneratorTile | SplineTile):
                positions[(clip.tile_id, abs(du))].append(u)
            else:
                works.append(Work(tile.name, lambda t=tile, a=float(u[0]), d=du, k=i1 - i0:
                                  t.render(a, d, k, q)))  # fmt: skip
            for fade, x in ((clip.fade_in, pos), (clip.fade_out, clip.duration - pos)):
                if fade.length > 0:
                    fades[fade.shape].append(x[x < fade.length] / fade.length)
    for (tile_id, du), parts in positions.items():
        tile = project.tile(tile_id)
        u = np.sort(np.concatenate(parts))
        lo, hi = float(u[0]), float(u[-1])
        if isinstance(tile, SplineTile):
            works.append(Work(tile.name, lambda t=tile, u=u, lo=lo, hi=hi:
                              t._values(u, lo, hi)))  # fmt: skip
            continue
        assert isinstance(tile, GeneratorTile)  # positions holds generator and spline tiles only
        nyquist = 0.5 / du
        params = dict(tile.params)
        works.append(Work(tile.name, lambda t=tile, u=u, lo=lo, hi=hi, f=nyquist, p=params:
                          band_limited(t.generator, u, f, t.duration, p,
                                       lambda v: t._values(v, lo, hi), (lo, hi))))  # fmt: skip
    for (tile_id, step), starts in recordings.items():
        recording = project.tile(tile_id)
        assert isinstance(recording, SampledTile)  # recordings holds sampled tiles only
        works += _recording_work(recording, step, starts, q)
    for shape, parts in fades.items():
        x = np.concatenate(parts)
        works.append(Work(f"{shape} fades", lambda s=shape, x=x: fade_in_gain(x, s)))
    return works


def run_all(works: list[Work]) -> None:
    """Run every evaluation once (what the floor's timing measures)."""
    for work in works:
        work.run()
