"""Live playback: a paced stream of coefficient blocks rendered from the newest project state.

Qt-free. The stream is what a device's `play` pulls block by block; `set_project` only swaps a
reference, and the next block pulled is rendered from the new state (mixer caches make that a
re-sum of the touched blocks), so an edit is felt within about one block period.

Chunks are rendered one ahead on a worker thread while the current one plays, so the stream's
own thread only slices blocks out of them (a chunk of a 20k-clip project takes 10-30 ms to
render, as long as the lead); an edit re-renders the current chunk at once.

A paced stream hands each block over `lead` before its first sample plays (the device's lead: 30 ms
for the sim, 100 ms for a USB knob streaming from its own process; its clock starts when
the first block is handed over, so a slow first render does not make the next blocks burst) and
counts the blocks it hands over later than that lead (LatenessMeter): what a device with a wall
clock feels as an underrun.

A position project plays as tables over angle (LiveTables); an edit rebuilds the tables and swaps
them in, and a device that reads the program's `table` at every chunk (the sim: every 50 ms)
plays the new ones from its next chunk.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Iterable, Iterator
from concurrent.futures import FIRST_COMPLETED, Future, ThreadPoolExecutor, wait
from dataclasses import dataclass, replace

import numpy as np

from timeline.errors import HapticTimelineError
from timeline.model import Project
from timeline.plugins.device_protocol import (
    CoefficientBlock,
    LatenessMeter,
    PositionProgram,
    PositionTable,
)
from timeline.plugins.device_protocol.lateness import LEAD_SECONDS
from timeline.plugins.track_kinds import track_kind
from timeline.rendering import playback
from timeline.rendering.mixer import Mixer
from timeline.signal.render_presets import DEFAULT_QUALITY

BLOCK_SECONDS = 0.01
CHUNK_SECONDS = 0.5


@dataclass(eq=False)
class _Chunk:
    """Samples [first, end) of one project version at the device rate: rendered, or rendering."""

    version: int
    first: int
    end: int
    future: Future[CoefficientBlock]
    block: CoefficientBlock | None = None

    def covers(self, i: int, count: int) -> bool:
        return self.first <= i and i + count <= self.end


@dataclass
class StreamState:
    """Where the stream is and which project version it is playing."""

    position: float = 0.0
    version: int = 0
    live_version: int = -1  # version of the last block handed to the device
    live_at: float = 0.0  # perf_counter when that version first went out


class LiveStream:
    """Iterates CoefficientBlocks over [start, stop) (looping if asked), in real time if paced."""

    def __init__(
        self,
        project: Project,
        rate: float,
        start: float,
        stop: float,
        loop: bool = False,
        tracks: Iterable[str] | None = None,
        paced: bool = True,
        quality: str = DEFAULT_QUALITY,
        mixer: Mixer | None = None,
        asked: float | None = None,
        lead: float = LEAD_SECONDS,
    ) -> None:
        """`mixer` may be one kept warm between plays; `asked` is the perf_counter time Play was
        pressed (the first block's latency counts from it; default: now); `lead` how far ahead
        of its play a block is handed over (the device's DeviceInfo.lead)."""
        self.rate, self.start, self.stop, self.loop = rate, start, max(stop, start), loop
        self.tracks = None if tracks is None else list(tracks)
        self.paced, self.quality = paced, quality
        self.mixer = mixer or Mixer(cache_bytes=256 * 2**20)
        self.lead = lead
        self.lateness = LatenessMeter(lead, asked)
        self.state = StreamState(position=start)
        self._project = project
        self._chunk: _Chunk | None = None  # playing
        self._next: _Chunk | None = None  # the one after it, rendering ahead
        self._edit: _Chunk | None = None  # the newest state from where it plays, rendering
        self._worker: ThreadPoolExecutor | None = None
        self._rendering = threading.Lock()  # one render at a time through the mixer
        self._stopped = threading.Event()
        self.on_block: Callable[[StreamState], None] | None = None
        self.mass = _has_mass(project)

    def set_project(self, project: Project) -> int:
        """Play a new project state from the next block on; returns its version."""
        self._project = project
        self.state.version += 1
        return self.state.version

    def stop_stream(self) -> None:
        """End the stream after the current block."""
        self._stopped.set()

    def __iter__(self) -> Iterator[CoefficientBlock]:
        self._worker = ThreadPoolExecutor(max_workers=1, thread_name_prefix="chunk ahead")
        try:
            yield from self._blocks()
        finally:
            self._worker.shutdown(wait=False, cancel_futures=True)

    def _blocks(self) -> Iterator[CoefficientBlock]:
        n = max(1, round(BLOCK_SECONDS * self.rate))
        t = self.start
        clock: float | None = None  # perf_counter when the first block was handed over
        played = 0.0
        while not self._stopped.is_set():
            if t >= self.stop - 0.5 / self.rate:
                if not self.loop or self.stop <= self.start:
                    return
                t = self.start
            count = min(n, max(1, round((self.stop - t) * self.rate)))
            slot = None if clock is None or not self.paced else clock + played - self.lead
            version, block = self._block(t, count, slot)
            if self.paced:
                now = time.perf_counter()
                clock = now if clock is None else clock
                delay = clock + played - self.lead - now
                if delay > 0:
                    time.sleep(delay)
                    now = time.perf_counter()
                self.lateness.handed(clock + played, now)
            state = self.state
            if state.live_version != version:
                state.live_version, state.live_at = version, time.perf_counter()
            state.position = t
            if self.on_block:
                self.on_block(state)
            yield block
            t += count / self.rate
            played += count / self.rate

    def _block(self, t: float, count: int, slot: float | None) -> tuple[int, CoefficientBlock]:
        """Samples [t, t + count/rate) and the project version they come from.

        From the newest version when its chunk is ready by `slot` (the block's hand-over time;
        None: wait for it), else from the chunk already playing, or the one rendered after it:
        an edit is felt a block or two later rather than the block being late.
        """
        version, i = self.state.version, round(t * self.rate)
        chunk = self._chunk
        fits = chunk is not None and chunk.covers(i, count)
        if chunk is None or not fits or chunk.version != version:
            fresh = self._fresh(version, t, count, slot if fits else None)
            if fresh is not None:
                chunk = self._adopt(fresh)
        assert chunk is not None and chunk.block is not None
        block, i0 = chunk.block, i - chunk.first
        m = None if block.m is None else block.m[i0 : i0 + count]
        cut = CoefficientBlock(
            block.d[i0 : i0 + count], block.k[i0 : i0 + count], block.b[i0 : i0 + count], m
        )
        return chunk.version, cut

    def _fresh(self, version: int, t: float, count: int, slot: float | None) -> _Chunk | None:
        """A chunk of `version` from t: the one rendered ahead, or one rendering on the worker,
        waited for until `slot`. None for `slot` means no chunk plays on: then, when paced, the
        chunk rendered ahead from an older version will do too, whichever is ready first."""
        i = round(t * self.rate)
        if self._next is not None and self._next.version == version and self._next.covers(i, count):
            return self._next  # the usual case: the chunk rendered ahead
        seconds = max(CHUNK_SECONDS, count / self.rate)
        edit = self._edit
        if edit is None or edit.version != version or not edit.covers(i, count):
            if edit is not None:
                edit.future.cancel()  # a newer state or another place: not wanted any more
            edit = self._edit = self._submit(version, t, seconds)
        if edit is None:  # no worker (not iterating): render here
            return self._rendered_now(version, t, seconds)
        if slot is not None:
            try:
                edit.future.result(timeout=max(0.0, slot - time.perf_counter()))
            except TimeoutError:
                return None  # not ready in time: the playing chunk goes on a little longer
            return edit
        ahead = [c for c in (edit, self._next) if c is not None and c.covers(i, count)]
        ahead = ahead if self.paced else [edit]  # unpaced: always the newest state
        ahead = [c for c in ahead if not c.future.cancelled()]
        if not ahead:
            return self._rendered_now(version, t, seconds)
        ready, _ = wait([c.future for c in ahead], return_when=FIRST_COMPLETED)
        return next(c for c in ahead if c.future in ready)

    def _rendered_now(self, version: int, t: float, seconds: float) -> _Chunk:
        """[t, t + seconds) of the newest state, rendered on this thread."""
        stop = min(self.stop, t + seconds)
        done: Future[CoefficientBlock] = Future()
        done.set_result(self.render(self._project, t, stop))
        i = round(t * self.rate)
        return _Chunk(version, i, i + max(1, round((stop - t) * self.rate)), done)

    def _adopt(self, chunk: _Chunk) -> _Chunk:
        """Play from this chunk, and render the one after it ahead."""
        chunk.block = chunk.future.result()
        if chunk is self._edit:
            self._edit = None
        if self._next is not None and self._next is not chunk:
            self._next.future.cancel()
        self._chunk = chunk
        t = chunk.end / self.rate
        if t >= self.stop - 0.5 / self.rate:
            t = self.start if self.loop and self.stop > self.start else self.stop
        self._next = self._submit(self.state.version, t, CHUNK_SECONDS)
        return chunk

    def _submit(self, version: int, t: float, seconds: float) -> _Chunk | None:
        """Start rendering [t, t + seconds) of the newest state on the worker (None: no worker
        or nothing left to render)."""
        stop = min(self.stop, t + seconds)
        if self._worker is None or stop <= t:
            return None
        future = self._worker.submit(self.render, self._project, t, stop)
        i = round(t * self.rate)
        return _Chunk(version, i, i + max(1, round((stop - t) * self.rate)), future)

    def render(self, project: Project, t0: float, t1: float) -> CoefficientBlock:
        """The project's coefficients d, k, b (and m) on [t0, t1) at the device rate."""
        n = max(1, round((t1 - t0) * self.rate))
        terms = {"d": np.zeros(n), "k": np.zeros(n), "b": np.zeros(n), "m": np.zeros(n)}
        with self._rendering:  # the mixer's arrays are its own until the next render
            layers = self.mixer.render(project, t0, t1, self.rate, self.quality, self.tracks)
            for kind_id, values in layers.items():
                terms[track_kind(kind_id).term][: len(values)] += values
        return CoefficientBlock(
            terms["d"], terms["k"], terms["b"], terms["m"] if self.mass else None
        )


def _has_mass(project: Project) -> bool:
    return any(track_kind(t.kind).term == "m" and t.clips for t in project.tracks)


class LiveTables:
    """Position tables that edits replace while they play: the `live` source of a program."""

    def __init__(self, sweep: PositionProgram) -> None:
        self._table = sweep.table
        self.program = replace(sweep, live=self.current)

    def current(self) -> PositionTable:
        """The newest tables (a device asks once per chunk)."""
        return self._table

    def set_project(self, project: Project) -> None:
        """Play the tables of a new project state (silence if it has no clips left)."""
        try:
            table, _ = playback.position_table(project)
        except HapticTimelineError:
            table = PositionTable(self._table.start, self._table.rate, np.zeros(1))
        self._table = table  # one reference swap: a device reads the whole table or the old one
