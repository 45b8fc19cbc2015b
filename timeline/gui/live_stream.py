"""Live playback: a paced stream of coefficient blocks rendered from the newest project state.

Qt-free. The stream is what a device's `play` pulls block by block; `set_project` only swaps a
reference, and the next block pulled is rendered from the new state (mixer caches make that a
re-sum of the touched blocks), so an edit is felt within about one block period.

A paced stream hands each block over `lead` before its first sample plays (its clock starts when
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
    ) -> None:
        """`mixer` may be one kept warm between plays; `asked` is the perf_counter time Play was
        pressed (the first block's latency counts from it; default: now)."""
        self.rate, self.start, self.stop, self.loop = rate, start, max(stop, start), loop
        self.tracks = None if tracks is None else list(tracks)
        self.paced, self.quality = paced, quality
        self.mixer = mixer or Mixer(cache_bytes=256 * 2**20)
        self.lateness = LatenessMeter(LEAD_SECONDS, asked)
        self.state = StreamState(position=start)
        self._project = project
        self._chunk: tuple[int, float, CoefficientBlock] | None = None  # (version, t0, block)
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
            block = self._block(t, count)
            if self.paced:
                now = time.perf_counter()
                clock = now if clock is None else clock
                delay = clock + played - LEAD_SECONDS - now
                if delay > 0:
                    time.sleep(delay)
                    now = time.perf_counter()
                self.lateness.handed(clock + played, now)
            state = self.state
            if state.live_version != state.version:
                state.live_version, state.live_at = state.version, time.perf_counter()
            state.position = t
            if self.on_block:
                self.on_block(state)
            yield block
            t += count / self.rate
            played += count / self.rate

    def _block(self, t: float, count: int) -> CoefficientBlock:
        """Samples [t, t + count/rate) from the cached chunk, re-rendered if the state changed."""
        version = self.state.version
        chunk = self._chunk
        i0 = 0 if chunk is None else round((t - chunk[1]) * self.rate)
        if chunk is None or chunk[0] != version or i0 < 0 or i0 + count > len(chunk[2]):
            chunk_stop = min(self.stop, t + max(CHUNK_SECONDS, count / self.rate))
            chunk = self._chunk = (version, t, self.render(self._project, t, chunk_stop))
            i0 = 0
        block = chunk[2]
        m = None if block.m is None else block.m[i0 : i0 + count]
        return CoefficientBlock(
            block.d[i0 : i0 + count], block.k[i0 : i0 + count], block.b[i0 : i0 + count], m
        )

    def render(self, project: Project, t0: float, t1: float) -> CoefficientBlock:
        """The project's coefficients d, k, b (and m) on [t0, t1) at the device rate."""
        layers = self.mixer.render(project, t0, t1, self.rate, self.quality, self.tracks)
        n = max(1, round((t1 - t0) * self.rate))
        terms = {"d": np.zeros(n), "k": np.zeros(n), "b": np.zeros(n), "m": np.zeros(n)}
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
