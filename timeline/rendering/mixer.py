"""The mixer: render a project's layers (Equation 2 coefficients) to arrays, caching per clip.

Overlapping clips on a track add; tracks of one kind add into that kind's layer. Two caches keep
re-renders proportional to what changed:

* shapes: a clip's samples in tile units (before clip gain and track scale), keyed by what
  determines them (tile, source range, stretch, fades, sub-sample offset, length, rate,
  quality), so clips placed by duplicating or pasting share one evaluation;
* windows: each layer's output buffer for one (start, rate, length, quality), split into blocks.
  A re-render compares tracks and clips by identity (edits share unchanged ones), marks the
  blocks that the changed clips touch, and sums only those again, in the same order a fresh
  render uses, so the result is bit-identical to a render from scratch.

Placement is exact at any time and rate: a render's samples are k/rate for integers k (or
origin + k/rate for a start off the grid), a clip covers the k from its first sample on, and its
shape is evaluated in pieces that start at fixed sample counts from the clip's first sample. So a
render, the same range cut into chunks, export and play give the same bits.

Returned arrays are read-only. A window's buffer is updated in place only when no caller still
holds an earlier result (its reference count says so); otherwise it is copied first.

One mixer serves every thread: a render takes its windows out of the cache while it works and
puts them back when it is done, so two threads never sum into one buffer, and a render that fails
half way (a MemoryError, an overflow) leaves nothing half-summed behind: the next render of that
window starts fresh. The caches themselves are changed under a lock.
"""

from __future__ import annotations

import math
import sys
import threading
from collections import OrderedDict
from collections.abc import Callable, Iterable, Iterator
from dataclasses import astuple, dataclass
from itertools import chain
from typing import Generic, NamedTuple, TypeVar

import numpy as np

from timeline.errors import HapticTimelineError, RenderError
from timeline.model import Clip, Project, Track
from timeline.plugins.track_kinds import track_kind
from timeline.rendering.clip_render import clip_samples, on_grid, render_shape
from timeline.rendering.exact_sum import CANCELLING, Compensated
from timeline.signal import memory
from timeline.signal.render_presets import DEFAULT_QUALITY, QualityPreset, preset
from timeline.tiles import Tile

BLOCK = 32768  # output samples per block: the unit of re-summing after an edit
MAX_SAMPLES = 2**31  # one render call; longer renders go through render_chunks
PEAK_BYTES_PER_SAMPLE = 48  # measured peak memory of one layer's render, per output sample
# A window whose clips cover this many samples is summed by the compiled loop of
# timeline.signal.render_kernels (loading numba and the loops costs ~0.5 s CPU once per process,
# under a tenth of such a render); smaller renders (every example) keep numpy and never load numba.
COMPILED_SAMPLES = 50_000_000
PIECE = 2**16  # about this many samples per piece of a clip's shape (see piece_size)
MAX_PEAKS = 2**20  # pieces whose peaks are remembered (24 bytes each) before they are forgotten

_V = TypeVar("_V")


class _LRU(Generic[_V]):
    """A least-recently-used cache bounded by the total bytes of its values."""

    def __init__(self, max_bytes: int) -> None:
        self.max_bytes = max_bytes
        self.bytes = 0
        self._items: OrderedDict[object, tuple[_V, int]] = OrderedDict()

    def get(self, key: object) -> _V | None:
        item = self._items.get(key)
        if item is None:
            return None
        self._items.move_to_end(key)
        return item[0]

    def take(self, key: object) -> _V | None:
        """Remove and return the value (None if absent)."""
        item = self._items.pop(key, None)
        if item is None:
            return None
        self.bytes -= item[1]
        return item[0]

    def fits(self, nbytes: int) -> bool:
        return nbytes <= self.max_bytes // 4

    def put(self, key: object, value: _V, nbytes: int) -> None:
        if not self.fits(nbytes):
            return
        self.pop(key)
        self._items[key] = (value, nbytes)
        self.bytes += nbytes
        while self.bytes > self.max_bytes:
            _, (_, old) = self._items.popitem(last=False)
            self.bytes -= old

    def pop(self, key: object) -> None:
        item = self._items.pop(key, None)
        if item is not None:
            self.bytes -= item[1]

    def clear(self) -> None:
        self._items.clear()
        self.bytes = 0


@dataclass
class MixerStats:
    """Counters that show what the last renders actually recomputed.

    clip_renders / clip_hits: clips placed anew in a window (new or edited) / reused unchanged
    from an earlier render of it; shape_renders: clip shapes evaluated (clips that share a shape
    share one evaluation); block_sums / block_hits: output blocks summed again / reused.
    """

    clip_renders: int = 0
    clip_hits: int = 0
    block_sums: int = 0
    block_hits: int = 0
    shape_renders: int = 0

    def add(self, other: MixerStats) -> None:
        """Add another render's counters to these."""
        for name, value in vars(other).items():
            setattr(self, name, getattr(self, name) + value)


class _Grid(NamedTuple):
    """The output grid of one render: origin + (first + i)/rate for i < n, at one quality.

    origin is 0 when the render starts on the sample grid k/rate (then first is that k), else
    the render's start (and first counts from it).
    """

    origin: float
    first: int
    rate: float
    n: int
    quality: QualityPreset
    quality_key: tuple  # the preset's fields, cheap to hash in cache keys
    piece: int  # samples per piece of a clip shape at this rate

    @property
    def start(self) -> float:
        return self.origin + self.first / self.rate


def anchor(start: float, rate: float) -> tuple[float, int]:
    """(origin, first) of a render starting at `start`: (0, k) when start is on the grid k/rate."""
    k = on_grid(start, 0.0, rate)
    return (start, 0) if k is None else (0.0, k)


def piece_size(rate: float) -> int:
    """Samples per piece of a clip shape: near PIECE, and for an integer rate a multiple of its
    odd part, so a piece's start j * size / rate in the clip is an exact binary number."""
    if rate != math.floor(rate) or rate > 2**52:
        return PIECE
    size = int(rate)
    while size % 2 == 0:
        size //= 2
    while size * 2 <= PIECE:
        size *= 2
    return size


class _Placed:
    """A clip placed in a window: output samples [i0, i1) = weight * shape values.

    The clip's own samples are [c0, c0 + length) in the window's indices (c0 may be negative);
    its shape is evaluated in pieces of grid.piece samples from c0, the first at offset `phase`.
    """

    __slots__ = ("clip", "tile", "shape", "weight", "i0", "i1", "c0", "length", "phase")

    def __init__(self, clip: Clip, tile: Tile, shape: tuple, weight: float, i0: int, i1: int,
                 c0: int, length: int, phase: float) -> None:  # fmt: skip
        self.clip, self.tile, self.shape, self.weight = clip, tile, shape, weight
        self.i0, self.i1, self.c0, self.length, self.phase = i0, i1, c0, length, phase

    def same(self, other: _Placed) -> bool:
        return (self.shape == other.shape and self.weight == other.weight
                and self.i0 == other.i0 and self.i1 == other.i1
                and self.c0 == other.c0)  # fmt: skip


@dataclass
class _Part:
    """One track's clips placed in a window, and what they were placed from."""

    clips: tuple[Clip, ...]
    scale: float
    tiles: dict[str, tuple[Tile, str]]  # tile id -> (tile, key) the clips were placed from
    placed: list[_Placed]
    starts: np.ndarray  # i0 of each placement
    ends: np.ndarray  # i1 of each placement


class _Window:
    """A layer's output buffer on one grid, with the placements that were summed into it."""

    def __init__(self, n: int) -> None:
        self.buffer = np.zeros(n)
        self.buffer.setflags(write=False)
        self.parts: dict[str, _Part] = {}
        self.order: tuple[str, ...] = ()
        self.placed: list[_Placed] = []
        self.starts = np.zeros(0, dtype=np.int64)
        self.ends = np.zeros(0, dtype=np.int64)
        self.output: np.ndarray | None = None  # the buffer in a preset's other dtype

    @property
    def nbytes(self) -> int:
        return self.buffer.nbytes + (0 if self.output is None else self.output.nbytes)


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
    count = (stop - start) * rate
    if not math.isfinite(count):
        raise HapticTimelineError(
            f"{start:g} to {stop:g} at {rate:g} per unit is more samples than can be counted"
        )
    return int(round(count))


def _layers(
    project: Project, tracks: Iterable[str] | None, context: bool = False
) -> dict[str, list[tuple[Track, float]]]:
    """Kind id -> (track, scale) for the sounding tracks that have clips, in track order.

    Context tracks (kind.context) are left out, or with `context` are the only ones taken.
    """
    layers: dict[str, list[tuple[Track, float]]] = {}
    for track in active_tracks(project, tracks):
        if not track.clips:
            continue
        kind = track_kind(track.kind)
        if kind.context != context:
            continue
        if project.axis not in kind.axes:
            raise HapticTimelineError(
                f"track {track.name!r} is a {kind.id} track, which a {project.axis} project "
                "cannot use"
            )
        scale = track.gain * (kind.full_scale if track.full_scale is None else track.full_scale)
        layers.setdefault(kind.id, []).append((track, scale))
    return layers


class Mixer:
    """Renders projects, keeping clip-shape and per-window caches between calls."""

    def __init__(self, cache_bytes: int = 512 * 2**20) -> None:
        self._shapes: _LRU[np.ndarray] = _LRU(cache_bytes)
        self._peaks: dict[tuple, float] = {}  # piece key -> its largest magnitude (exact_sum)
        self._windows: _LRU[_Window] = _LRU(cache_bytes)
        self._lock = threading.Lock()  # held while the caches or stats change, never to render
        self.stats = MixerStats()

    def clear(self) -> None:
        """Forget all cached renders."""
        with self._lock:
            self._shapes.clear()
            self._peaks.clear()
            self._windows.clear()

    def render(
        self,
        project: Project,
        start: float = 0.0,
        stop: float | None = None,
        rate: float | None = None,
        quality: str | QualityPreset = DEFAULT_QUALITY,
        tracks: Iterable[str] | None = None,
        context: bool = False,
    ) -> dict[str, np.ndarray]:
        """Mapping kind id -> samples on [start, stop) at rate, for layers that have clips (SI).

        Context tracks (the source sound) are never part of it; with `context` only they are
        rendered, for listening. The arrays are read-only; copy one to change it.
        """
        rate = float(project.rate if rate is None else rate)
        stop = float(project.duration if stop is None else stop)
        start = float(start)
        n = grid_length(start, stop, rate)
        return self._render(project, *anchor(start, rate), n, rate, quality, tracks, context)

    def _render(
        self,
        project: Project,
        origin: float,
        first: int,
        n: int,
        rate: float,
        quality: str | QualityPreset,
        tracks: Iterable[str] | None,
        context: bool = False,
    ) -> dict[str, np.ndarray]:
        """Render the n samples origin + (first + i)/rate (see render)."""
        q = preset(quality)
        if n > MAX_SAMPLES:
            raise HapticTimelineError(
                f"{memory.count_text(n)} samples is too many for one render (at most "
                f"{MAX_SAMPLES:,}); render a shorter range or at a lower rate"
            )
        grid = _Grid(origin, first, rate, n, q, astuple(q), piece_size(rate))
        tile_keys: dict[str, str] = {}
        stats = MixerStats()
        result = {}
        layers = _layers(project, tracks, context)
        memory.require(
            n * len(layers) * PEAK_BYTES_PER_SAMPLE,
            f"rendering {memory.count_text(n)} samples of {len(layers)} layer(s)",
            "render a shorter range or at a lower rate",
        )
        try:
            for kind_id, layer in layers.items():
                key = (kind_id, origin, first, rate, n, grid.quality_key)
                try:
                    result[kind_id] = self._mix(project, layer, key, grid, tile_keys, stats)
                except RenderError as exc:
                    raise RenderError(f"the {kind_id} layer is {exc} {project.unit}"
                                      " (amplitudes too large to add up)") from None  # fmt: skip
        finally:
            with self._lock:
                self.stats.add(stats)
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
        origin, first = anchor(float(start), rate)
        step = max(1, int(round(chunk * rate)))
        for done in range(0, total, step):
            count = min(step, total - done)
            layers = self._render(project, origin, first + done, count, rate, quality, tracks)
            yield start + done / rate, layers

    # --- one layer in one window ---------------------------------------------------------------

    def _mix(
        self,
        project: Project,
        layer: list[tuple[Track, float]],
        key: tuple,
        grid: _Grid,
        tile_keys: dict[str, str],
        stats: MixerStats,
    ) -> np.ndarray:
        """One layer on the grid: the cached window brought up to date, or a new one.

        The window is out of the cache while this runs (another thread rendering the same window
        meanwhile starts its own) and goes back only when it is complete.
        """
        n = grid.n
        with self._lock:
            window = self._windows.take(key)
        if window is None:
            window = _Window(n)
        order = tuple(track.id for track, _ in layer)
        kept = [t for t in order if t in window.parts]
        # A new window, or tracks that changed their summing order, are summed whole.
        full = not window.parts or kept != [t for t in window.order if t in set(order)]
        dirty: list[tuple[int, int]] = [(0, n)] if full else []
        parts: dict[str, _Part] = {}
        for track, scale in layer:
            old = window.parts.get(track.id)
            if old is not None and self._unchanged(old, track, scale, project, tile_keys):
                parts[track.id] = old
                stats.clip_hits += len(old.placed)
                continue
            before = {} if old is None else {id(p.clip): p for p in old.placed}
            parts[track.id] = part = self._place(project, track, scale, grid, tile_keys, before)
            for p in part.placed:
                q = before.pop(id(p.clip), None)
                if q is not None and p.same(q):
                    stats.clip_hits += 1
                    continue
                stats.clip_renders += 1
                if not full:
                    dirty.append((p.i0, p.i1))
                    if q is not None:
                        dirty.append((q.i0, q.i1))
            if not full:
                dirty += [(q.i0, q.i1) for q in before.values()]
        if not full:
            for track_id in window.parts.keys() - parts.keys():
                dirty += [(p.i0, p.i1) for p in window.parts[track_id].placed]
        if order != window.order or any(parts[t] is not window.parts.get(t) for t in order):
            window.parts, window.order = parts, order
            chosen = [parts[track_id] for track_id in order]
            window.placed = list(chain.from_iterable(part.placed for part in chosen))
            window.starts = np.concatenate([part.starts for part in chosen])
            window.ends = np.concatenate([part.ends for part in chosen])
        blocks = _blocks(dirty, n)
        stats.block_hits += -(-n // BLOCK) - len(blocks)
        if blocks:
            if sys.getrefcount(window.buffer) > 2:  # a caller still holds the last result
                window.buffer = window.buffer.copy()
            window.buffer.setflags(write=True)
            try:
                self._sum(window, blocks, grid, stats)
            finally:
                window.buffer.setflags(write=False)
        out = _in_dtype(window, blocks, grid)
        with self._lock:
            self._windows.put(key, window, window.nbytes)
        return out

    def _unchanged(
        self, old: _Part, track: Track, scale: float, project: Project, tile_keys: dict[str, str]
    ) -> bool:
        """True when a track's part can be reused: same clips, scale and tile contents."""
        if old.scale != scale or old.clips != track.clips:
            return False
        tiles = project.tiles
        return all(
            tiles.get(tile_id) is tile or _tile_key(project, tile_id, tile_keys) == k
            for tile_id, (tile, k) in old.tiles.items()
        )

    def _place(
        self,
        project: Project,
        track: Track,
        scale: float,
        grid: _Grid,
        tile_keys: dict[str, str],
        before: dict[int, _Placed],
    ) -> _Part:
        """Place a track's clips on the grid, reusing `before` placements of the same clips."""
        origin, first, rate, n = grid.origin, grid.first, grid.rate, grid.n
        start = grid.start
        placed = []
        used = {}
        # clips wholly outside the window are never placed: visit only those that may touch it
        for clip in track.clips_between(start, origin + (first + n) / rate, 2.0 / rate):
            tile = project.tile(clip.tile_id)
            old = before.get(id(clip))
            if old and old.clip is clip and old.tile is tile and old.weight == scale * clip.gain:
                used[clip.tile_id] = (tile, old.shape[0])
                placed.append(old)
                continue
            c0, c1, phase = clip_samples(clip, origin, rate)
            c0, c1 = c0 - first, c1 - first
            i0, i1 = max(c0, 0), min(max(c1, 0), n)
            if i1 <= i0:
                continue
            tile_key = _tile_key(project, clip.tile_id, tile_keys)
            used[clip.tile_id] = (tile, tile_key)
            fi, fo = clip.fade_in, clip.fade_out
            shape = (tile_key, clip.source_in, clip.source_out, clip.stretch, clip.stretch_mode,
                     clip.loop_phase, clip.scale, clip.offset, clip.reverse, fi.length, fi.shape,
                     fo.length, fo.shape, phase, c1 - c0, rate, grid.quality_key)  # fmt: skip
            placed.append(_Placed(clip, tile, shape, scale * clip.gain, i0, i1, c0, c1 - c0,
                                  phase))  # fmt: skip
        starts = np.array([p.i0 for p in placed], dtype=np.int64)
        ends = np.array([p.i1 for p in placed], dtype=np.int64)
        return _Part(track.clips, scale, used, placed, starts, ends)

    def _sum(self, window: _Window, blocks: list[int], grid: _Grid, stats: MixerStats) -> None:
        """Sum the listed blocks again from their clips, in track and clip order."""
        out = window.buffer
        with np.errstate(over="ignore", invalid="ignore"):  # overflow is reported as one error
            if len(blocks) == -(-grid.n // BLOCK):
                self._sum_all(out, window, grid, stats)
                return
            members = _members(window, blocks, grid.n)
            adder = _adder(window.starts, window.ends)
            scratch = np.empty(BLOCK)
            pieces: dict[tuple, np.ndarray] = {}  # pieces in use, dropped after their last block
            for b in blocks:
                lo, hi = b * BLOCK, min((b + 1) * BLOCK, grid.n)
                acc = out[lo:hi]
                acc.fill(0.0)
                for p in members[b]:
                    self._add(out, p, max(p.i0, lo), min(p.i1, hi), grid, adder, scratch, stats,
                              pieces)  # fmt: skip
                self._resum_cancelled(out, b, members[b], grid, stats)
                _check_finite(acc, grid, lo)
        stats.block_sums += len(blocks)

    def _sum_all(self, out: np.ndarray, window: _Window, grid: _Grid, stats: MixerStats) -> None:
        """Sum every clip into the whole buffer: per sample the same order as block by block."""
        out.fill(0.0)
        scratch = np.empty(BLOCK)
        adder = _adder(window.starts, window.ends)
        size = grid.piece
        for p in window.placed:  # each sample's sum rounds alike however a clip is cut
            if p.length <= size:  # one piece (most clips): added here, without _add's loop
                x = self._piece(p, 0, grid, stats)
                adder(out[p.i0 : p.i1], x[p.i0 - p.c0 : p.i1 - p.c0], p.weight, scratch)
            else:
                self._add(out, p, p.i0, p.i1, grid, adder, scratch, stats)
        blocks = list(range(-(-grid.n // BLOCK)))
        for b, members in _members(window, blocks, grid.n).items():
            self._resum_cancelled(out, b, members, grid, stats)
        _check_finite(out, grid, 0)
        stats.block_sums += -(-grid.n // BLOCK)

    def _add(
        self,
        out: np.ndarray,
        p: _Placed,
        a: int,
        z: int,
        grid: _Grid,
        adder: Callable,
        scratch: np.ndarray,
        stats: MixerStats,
        pieces: dict[tuple, np.ndarray] | None = None,
    ) -> None:
        """out[a:z] += weight * the clip's values there, piece by piece.

        `pieces` keeps the pieces in use between calls; a piece is dropped from it once z passes
        its end.
        """
        size = grid.piece
        j = (a - p.c0) // size
        while a < z:
            lo = p.c0 + j * size
            hi = min(lo + size, p.c0 + p.length)
            key = (p.shape, j)
            x = None if pieces is None else pieces.get(key)
            if x is None:
                x = self._piece(p, j, grid, stats)
                if pieces is not None and hi > z:
                    pieces[key] = x
            elif pieces is not None and hi <= z:
                del pieces[key]
            e = min(z, hi)
            adder(out[a:e], x[a - lo : e - lo], p.weight, scratch)
            a, j = e, j + 1

    def _piece(self, p: _Placed, j: int, grid: _Grid, stats: MixerStats) -> np.ndarray:
        """Piece j of a clip's shape: grid.piece samples from sample j * grid.piece of the clip."""
        key = (p.shape, j)
        with self._lock:
            values = self._shapes.get(key)
        if values is not None:
            return values
        stats.shape_renders += 1
        size = grid.piece
        n = min(size, p.length - j * size)
        values = render_shape(p.clip, p.tile, p.phase + j * size / grid.rate, grid.rate, n,
                              grid.quality)  # fmt: skip
        values.setflags(write=False)
        peak = peak_of(values)
        with self._lock:
            self._shapes.put(key, values, values.nbytes)
            if len(self._peaks) >= MAX_PEAKS:
                self._peaks.clear()
            self._peaks[key] = peak
        return values

    def _peak(self, p: _Placed, j: int, grid: _Grid, stats: MixerStats) -> float:
        """The largest magnitude in piece j of a clip's shape (rendered only if forgotten)."""
        peak = self._peaks.get((p.shape, j))
        if peak is None:
            peak = peak_of(self._piece(p, j, grid, stats))
        return peak

    def _piece_range(self, p: _Placed, lo: int, hi: int, grid: _Grid) -> range:
        """Indices of the pieces of p within samples [lo, hi)."""
        a, z = max(p.i0, lo), min(p.i1, hi)
        return (
            range((a - p.c0) // grid.piece, (z - 1 - p.c0) // grid.piece + 1) if a < z else range(0)
        )

    def _resum_cancelled(
        self, out: np.ndarray, b: int, members: list[_Placed], grid: _Grid, stats: MixerStats
    ) -> None:
        """Sum block b again with compensation (exact_sum) if its terms' magnitudes may exceed
        CANCELLING times its largest result; other blocks keep their plain sum, bit for bit."""
        lo, hi = b * BLOCK, min((b + 1) * BLOCK, grid.n)
        bound = 0.0
        for p in members:
            pieces = self._piece_range(p, lo, hi, grid)
            bound += abs(p.weight) * max(
                (self._peak(p, j, grid, stats) for j in pieces), default=0.0
            )
        if not bound > CANCELLING * float(np.max(np.abs(out[lo:hi]), initial=0.0)):
            return
        exact = Compensated(hi - lo)
        for p in members:
            for j in self._piece_range(p, lo, hi, grid):
                x = self._piece(p, j, grid, stats)
                c = p.c0 + j * grid.piece
                a, z = max(p.i0, lo, c), min(p.i1, hi, c + len(x))
                exact.add(a - lo, z - lo, x[a - c : z - c], p.weight)
        out[lo:hi] = exact.result()


def peak_of(values: np.ndarray) -> float:
    """The largest magnitude of a piece (nan if it holds one; 0 when empty): in one compiled
    pass once numba is loaded, else numpy's max of the magnitudes (the same number)."""
    if not len(values):
        return 0.0
    if "timeline.signal.render_kernels" in sys.modules:
        from timeline.signal.render_kernels import peak_bits

        top = np.int64(peak_bits(values.view(np.int64))).view(np.float64)
        return math.nan if math.isnan(top) else float(top)
    return float(np.max(np.abs(values)))


def _numpy_add(out: np.ndarray, x: np.ndarray, weight: float, scratch: np.ndarray) -> None:
    """out += weight * x with numpy, a scratch-sized piece at a time: scale, then add."""
    step = len(scratch)
    for a in range(0, len(x), step):
        z = min(a + step, len(x))
        tmp = scratch[: z - a]
        np.multiply(x[a:z], weight, out=tmp)
        np.add(out[a:z], tmp, out=out[a:z])


def _adder(starts: np.ndarray, ends: np.ndarray) -> Callable:
    """How to add a clip or a piece of one, (out, x, weight, scratch) -> None.

    Both ways round the product, then add it (two roundings per sample, on one thread, whatever
    BLAS threads a loaded machine runs), so sums are bit-identical whichever is used and however
    a clip is cut (a full sum adds whole clips, a partial one block pieces). The compiled
    one-pass loop is taken once numba is loaded, or when the clips cover enough samples to
    repay loading it.
    """
    small = int((ends - starts).sum()) < COMPILED_SAMPLES
    if small and "timeline.signal.render_kernels" not in sys.modules:
        return _numpy_add
    from timeline.signal.render_kernels import scaled_add

    return lambda out, x, weight, scratch: scaled_add(out, x, weight)


def _check_finite(values: np.ndarray, grid: _Grid, first: int) -> None:
    """Raise one RenderError naming the first non-finite sample (values start at `first`)."""
    if math.isfinite(float(np.sum(values))) or np.isfinite(values).all():
        return
    at = first + int(np.flatnonzero(~np.isfinite(values))[0])
    raise RenderError(f"not a finite number at {grid.start + at / grid.rate:.6g}")


def _in_dtype(window: _Window, blocks: list[int], grid: _Grid) -> np.ndarray:
    """The window in the preset's dtype: its float64 buffer, or a copy updated block by block."""
    dtype = grid.quality.numpy_dtype
    if dtype == window.buffer.dtype:
        return window.buffer
    if window.output is None or len(blocks) == -(-grid.n // BLOCK):
        window.output = window.buffer.astype(dtype)
    elif blocks:
        if sys.getrefcount(window.output) > 2:  # a caller still holds the last result
            window.output = window.output.copy()
        window.output.setflags(write=True)
        for b in blocks:
            window.output[b * BLOCK : (b + 1) * BLOCK] = window.buffer[b * BLOCK : (b + 1) * BLOCK]
    window.output.setflags(write=False)
    return window.output


def _tile_key(project: Project, tile_id: str, memo: dict[str, str]) -> str:
    key = memo.get(tile_id)
    if key is None:
        key = memo[tile_id] = project.tile(tile_id).key
    return key


def _blocks(ranges: list[tuple[int, int]], n: int) -> list[int]:
    """Sorted indices of the blocks that the sample ranges touch."""
    if not ranges:
        return []
    if any(lo <= 0 and hi >= n for lo, hi in ranges):
        return list(range(-(-n // BLOCK)))
    touched = set()
    for lo, hi in ranges:
        touched.update(range(lo // BLOCK, (hi - 1) // BLOCK + 1))
    return sorted(touched)


def _members(window: _Window, blocks: list[int], n: int) -> dict[int, list[_Placed]]:
    """Block index -> the placements overlapping it, in summing order."""
    members: dict[int, list[_Placed]] = {b: [] for b in blocks}
    runs: list[list[int]] = []
    for b in blocks:
        if runs and runs[-1][-1] == b - 1:
            runs[-1].append(b)
        else:
            runs.append([b])
    for run in runs:
        lo, hi = run[0] * BLOCK, min((run[-1] + 1) * BLOCK, n)
        first, last = run[0], run[-1]
        hits = np.flatnonzero((window.starts < hi) & (window.ends > lo))
        for j in hits.tolist():
            p = window.placed[j]
            for b in range(max(p.i0 // BLOCK, first), min((p.i1 - 1) // BLOCK, last) + 1):
                members[b].append(p)
    return members


_default_mixer = Mixer()


def render(
    project: Project,
    start: float = 0.0,
    stop: float | None = None,
    rate: float | None = None,
    quality: str | QualityPreset = DEFAULT_QUALITY,
    tracks: Iterable[str] | None = None,
    context: bool = False,
) -> dict[str, np.ndarray]:
    """Render a project's layers with the shared mixer (see Mixer.render)."""
    return _default_mixer.render(project, start, stop, rate, quality, tracks, context)


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
