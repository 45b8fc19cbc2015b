"""The mixer: render a project's layers (Equation 2 coefficients) to arrays, caching per clip.

Overlapping clips on a track add; tracks of one kind add into that kind's layer. Results are
cached per clip and per block of output, so after one edit only the blocks that the edited clip
touches are summed again.
"""

from __future__ import annotations

import math
from collections import OrderedDict
from collections.abc import Iterable, Iterator
from dataclasses import dataclass

import numpy as np

from timeline.clip_render import clip_sample_range, render_clip
from timeline.errors import HapticTimelineError, RenderError
from timeline.kinds import track_kind
from timeline.model import Clip, Project, Track
from timeline.quality import DEFAULT_QUALITY, QualityPreset, preset
from timeline.tiles import Tile

BLOCK = 8192  # output samples per cached block
MAX_SAMPLES = 2**31  # one render call; longer renders go through render_chunks


class _LRU:
    """A least-recently-used cache of numpy arrays bounded by total bytes."""

    def __init__(self, max_bytes: int) -> None:
        self.max_bytes = max_bytes
        self.bytes = 0
        self._items: OrderedDict[object, np.ndarray] = OrderedDict()

    def get(self, key: object) -> np.ndarray | None:
        value = self._items.get(key)
        if value is not None:
            self._items.move_to_end(key)
        return value

    def put(self, key: object, value: np.ndarray) -> None:
        if value.nbytes > self.max_bytes // 4 or key in self._items:
            return
        value.setflags(write=False)
        self._items[key] = value
        self.bytes += value.nbytes
        while self.bytes > self.max_bytes:
            _, old = self._items.popitem(last=False)
            self.bytes -= old.nbytes

    def clear(self) -> None:
        self._items.clear()
        self.bytes = 0


@dataclass
class MixerStats:
    """Counters that show what the last renders actually recomputed."""

    clip_renders: int = 0
    clip_hits: int = 0
    block_sums: int = 0
    block_hits: int = 0


@dataclass(frozen=True)
class _Contribution:
    clip: Clip
    tile: Tile
    scale: float
    i0: int
    i1: int


def active_tracks(project: Project, tracks: Iterable[str] | None = None) -> list[Track]:
    """Tracks that sound: chosen by id or name (all if None), minus muted, honouring solo."""
    chosen = list(project.tracks)
    if tracks is not None:
        wanted = set(tracks)
        known = {t.id for t in chosen} | {t.name for t in chosen}
        missing = sorted(wanted - known)
        if missing:
            raise HapticTimelineError(f"the project has no track named {missing[0]!r}")
        chosen = [t for t in chosen if t.id in wanted or t.name in wanted]
    if any(t.solo for t in chosen):
        chosen = [t for t in chosen if t.solo]
    return [t for t in chosen if not t.mute]


def grid_length(start: float, stop: float, rate: float) -> int:
    """Number of output samples on [start, stop) at the rate."""
    for name, value in (("start", start), ("stop", stop), ("rate", rate)):
        if not math.isfinite(value):
            raise HapticTimelineError(f"the render {name} must be a finite number, not {value}")
    if rate <= 0:
        raise HapticTimelineError(f"the render rate must be positive, not {rate}")
    if stop < start:
        raise HapticTimelineError(f"the render stops ({stop}) before it starts ({start})")
    return int(round((stop - start) * rate))


class Mixer:
    """Renders projects, keeping per-clip and per-block caches between calls."""

    def __init__(self, cache_bytes: int = 512 * 2**20) -> None:
        self._clips = _LRU(cache_bytes)
        self._blocks = _LRU(cache_bytes)
        self.stats = MixerStats()

    def clear(self) -> None:
        """Forget all cached renders."""
        self._clips.clear()
        self._blocks.clear()

    def render(
        self,
        project: Project,
        start: float = 0.0,
        stop: float | None = None,
        rate: float | None = None,
        quality: str | QualityPreset = DEFAULT_QUALITY,
        tracks: Iterable[str] | None = None,
    ) -> dict[str, np.ndarray]:
        """Mapping kind id -> samples on [start, stop) at rate, for layers that have clips (SI)."""
        q = preset(quality)
        rate = float(project.rate if rate is None else rate)
        stop = float(project.duration if stop is None else stop)
        n = grid_length(start, stop, rate)
        if n > MAX_SAMPLES:
            raise HapticTimelineError(
                f"{n} samples is too many for one render; use render_chunks for long ranges"
            )
        layers: dict[str, list[_Contribution]] = {}
        for track in active_tracks(project, tracks):
            if not track.clips:
                continue
            kind = track_kind(track.kind)
            if project.axis not in kind.axes:
                raise HapticTimelineError(
                    f"track {track.name!r} is a {kind.id} track, which a {project.axis} project "
                    "cannot use"
                )
            scale = track.gain * (kind.full_scale if track.full_scale is None else track.full_scale)
            contributions = layers.setdefault(kind.id, [])
            for clip in track.clips:
                i0, i1 = clip_sample_range(clip, start, rate, n)
                if i1 > i0:
                    contributions.append(
                        _Contribution(clip, project.tile(clip.tile_id), scale, i0, i1)
                    )
        key = (float(start), rate, q.name)
        result = {}
        for kind_id, contributions in layers.items():
            out = self._mix(kind_id, contributions, key, n, q)
            bad = ~np.isfinite(out)
            if bad.any():
                t = start + int(np.flatnonzero(bad)[0]) / rate
                raise RenderError(
                    f"the {kind_id} layer is not a finite number at {t:.6g} {project.unit}"
                    " (amplitudes too large to add up)"
                )
            result[kind_id] = out.astype(q.numpy_dtype, copy=False)
        return result

    def render_chunks(
        self,
        project: Project,
        start: float = 0.0,
        stop: float | None = None,
        rate: float | None = None,
        quality: str | QualityPreset = DEFAULT_QUALITY,
        tracks: Iterable[str] | None = None,
        chunk: float = 10.0,
    ) -> Iterator[tuple[float, dict[str, np.ndarray]]]:
        """Render a long range piece by piece: yields (chunk start, layers) with bounded memory."""
        rate = float(project.rate if rate is None else rate)
        stop = float(project.duration if stop is None else stop)
        total = grid_length(start, stop, rate)
        step = max(1, int(round(chunk * rate)))
        for first in range(0, total, step):
            count = min(step, total - first)
            t0 = start + first / rate
            yield t0, self.render(project, t0, t0 + count / rate, rate, quality, tracks)

    def _mix(
        self,
        kind_id: str,
        contributions: list[_Contribution],
        key: tuple,
        n: int,
        q: QualityPreset,
    ) -> np.ndarray:
        out = np.zeros(n)
        per_block: dict[int, list[_Contribution]] = {}
        for c in contributions:
            for b in range(c.i0 // BLOCK, (c.i1 - 1) // BLOCK + 1):
                per_block.setdefault(b, []).append(c)
        rendered: dict[int, np.ndarray] = {}  # per call, so a clip too big to cache renders once
        for b, members in per_block.items():
            lo, hi = b * BLOCK, min((b + 1) * BLOCK, n)
            block_key = (
                kind_id,
                key,
                lo,
                hi,
                tuple((c.scale, c.clip, c.tile.key) for c in members),
            )
            cached = self._blocks.get(block_key)
            if cached is not None:
                self.stats.block_hits += 1
                out[lo:hi] = cached
                continue
            self.stats.block_sums += 1
            acc = out[lo:hi]
            for c in members:
                values = rendered.get(id(c))
                if values is None:
                    values = rendered[id(c)] = self._clip_values(c, key, q)
                a, z = max(c.i0, lo), min(c.i1, hi)
                segment = values[a - c.i0 : z - c.i0]
                if c.scale == 1.0:
                    acc[a - lo : z - lo] += segment
                else:
                    acc[a - lo : z - lo] += c.scale * segment
            self._blocks.put(block_key, acc.copy())
        return out

    def _clip_values(self, c: _Contribution, key: tuple, q: QualityPreset) -> np.ndarray:
        clip_key = (c.clip, c.tile.key, key, c.i0, c.i1)
        values = self._clips.get(clip_key)
        if values is not None:
            self.stats.clip_hits += 1
            return values
        self.stats.clip_renders += 1
        start, rate, _ = key
        values = render_clip(c.clip, c.tile, start + c.i0 / rate, rate, c.i1 - c.i0, q)
        self._clips.put(clip_key, values)
        return values


_default_mixer = Mixer()


def render(
    project: Project,
    start: float = 0.0,
    stop: float | None = None,
    rate: float | None = None,
    quality: str | QualityPreset = DEFAULT_QUALITY,
    tracks: Iterable[str] | None = None,
) -> dict[str, np.ndarray]:
    """Render a project's layers with the shared mixer (see Mixer.render)."""
    return _default_mixer.render(project, start, stop, rate, quality, tracks)


def render_chunks(
    project: Project,
    start: float = 0.0,
    stop: float | None = None,
    rate: float | None = None,
    quality: str | QualityPreset = DEFAULT_QUALITY,
    tracks: Iterable[str] | None = None,
    chunk: float = 10.0,
) -> Iterator[tuple[float, dict[str, np.ndarray]]]:
    """Render a long range in chunks with the shared mixer (see Mixer.render_chunks)."""
    return _default_mixer.render_chunks(project, start, stop, rate, quality, tracks, chunk)
