"""Time projects played on the sim and the USB knob from a process of its own (Qt-free).

In the editor's process the stream's renderer and the hand-over of blocks share the interpreter
lock with the GUI thread, and a C++ call made from Python there (a scene update, a paint) holds
it for 0.1-1.4 s at high load: blocks go out late. Here a child process (spawn) opens the device,
owns a Mixer and the LiveStream, and runs `device.play(stream, hand)`; nothing the editor's
threads do can delay a block. The USB knob is opened only here (its transfers run in the stream
process it starts, device.usb.process): the editor's process never holds the device, so a failed
child or editor ends in the stream process's STOP, or the knob's watchdog ramp, never in torque
held. The host sends it project versions as the designer edits, and gets
back telemetry, where the stream is, its late-block counts and the play's ending.

A project crosses the pipe as a delta against the last one sent (`delta`, `rebuild`): the tracks
and tiles whose objects changed (the model is immutable, so an unchanged part is the same
object), and the ids of the rest. Only what the mixer reads crosses (axis, rate, tracks, tiles).

Messages, host to child: ("warm", delta, start), ("play", delta, start, stop, loop, tracks, hand,
asked, number), ("edit", delta, version), ("stop",), ("close",). Child to host, each message
after the number of the play it belongs to (0 before any): ("ready", DeviceInfo) or ("error",
sentence) once opened; while playing ("part", LiveTelemetry), ("at", position, live version,
Lateness), then ("done", sentence or "", Lateness). The host takes the newest play's only.
"""

from __future__ import annotations

import gc
import multiprocessing
import queue
import sys
import threading
import time
from collections.abc import Callable, Iterable
from contextlib import suppress
from dataclasses import dataclass
from multiprocessing.connection import Connection
from typing import Any

from immutables import Map

from timeline.errors import DeviceError, HapticTimelineError
from timeline.model import Project, Track, map_changes
from timeline.plugins.device_protocol import (
    CoefficientBlock,
    Device,
    DeviceInfo,
    Hand,
    Lateness,
    LiveTelemetry,
    open_device,
)
from timeline.plugins.device_protocol.child_process import (
    end_child,
    ordinary,
    prefer_real_time,
)
from timeline.rendering.mixer import Mixer

from .job_errors import unexpected
from .live_stream import CHUNK_SECONDS, LiveStream, StreamState

START_SECONDS = 60.0  # a child that has not opened the device by then is not coming
END_SECONDS = 30.0  # a play not ended this long after its stop is stuck (USB transfers time out)
# The playing thread needs the lock for a moment every 10 ms block; the chunk-ahead worker's
# render (Python bookkeeping between numpy calls) hands it over after this long, not 5 ms.
SWITCH_SECONDS = 0.001


@dataclass(frozen=True)
class Delta:
    """A project as the tracks and tiles that changed since the last one sent.

    `tracks` holds, in order, each track or (unchanged) its id; `tiles` the new or changed
    tiles, `gone` the ids of tiles no longer there (both empty when the tile map is the same).
    """

    axis: str
    rate: float
    tracks: tuple[Track | str, ...]
    tiles: dict[str, Any]
    gone: tuple[str, ...]


def delta(old: Project | None, new: Project) -> Delta:
    """What crosses the pipe for `new` when the child holds `old` (None: everything)."""
    before = {} if old is None else {t.id: t for t in old.tracks}
    tracks = tuple(t.id if before.get(t.id) is t else t for t in new.tracks)
    if old is None:
        return Delta(new.axis, new.rate, tracks, dict(new.tiles), ())
    if new.tiles is old.tiles:
        return Delta(new.axis, new.rate, tracks, {}, ())
    changed, gone = map_changes(old.tiles, new.tiles)
    return Delta(new.axis, new.rate, tracks, changed, gone)


def rebuild(old: Project | None, change: Delta) -> Project:
    """The project `change` stands for, given the one it was made against."""
    before = {} if old is None else {t.id: t for t in old.tracks}
    tracks = tuple(before[t] if isinstance(t, str) else t for t in change.tracks)
    if old is None:
        tiles = Map(change.tiles)
    elif change.tiles or change.gone:
        editing = old.tiles.mutate()
        for k, v in change.tiles.items():
            editing[k] = v
        for k in change.gone:
            del editing[k]
        tiles = editing.finish()
    else:
        tiles = old.tiles
    return Project(axis=change.axis, rate=change.rate, tracks=tracks, tiles=tiles)


class PlayProcess:
    """The host's end: a child process that opened the device and plays streams on request.

    One play at a time; messages are read with `take` (never blocking) and `wait_done`.
    """

    def __init__(self, device_name: str) -> None:
        context = multiprocessing.get_context("spawn")  # no fork of a process running Qt threads
        child_in, self._to_child = context.Pipe(duplex=False)
        self._warmed, child_warmed = context.Pipe(duplex=False)
        self._from_child = context.Queue()  # the child's puts never block on a stalled host
        self.process = context.Process(
            target=serve, args=(child_in, self._from_child, child_warmed, device_name),
            daemon=False, name="play process",
        )  # fmt: skip  # not daemonic: the USB knob's stream process is its child; `close` ends it
        self.process.start()
        child_in.close()
        child_warmed.close()
        self.device_name = device_name
        self._sending = threading.Lock()  # one delta at a time against `_sent`
        self._warming = threading.Lock()  # one warm-up at a time waits for its answer
        self._sent: Project | None = None  # the project the child holds
        self._plays = 0  # plays asked for: the newest one's number
        try:
            message = self._from_child.get(timeout=START_SECONDS)
        except queue.Empty:
            self.close()
            raise HapticTimelineError("the play process did not open the device") from None
        _, kind, answer = message
        if kind == "error":
            self.close()
            raise HapticTimelineError(answer)
        self.info: DeviceInfo = answer  # what the device declared as it opened

    @property
    def alive(self) -> bool:
        return self.process.is_alive()

    def send(self, kind: str, project: Project, *args: Any) -> None:
        """Send a message carrying `project` as a delta against the last one sent."""
        with self._sending:
            change = delta(self._sent, project)
            if kind == "play":
                self._plays += 1
                args = (*args, self._plays)  # the child tags the play's messages with it
            try:
                self._to_child.send((kind, change, *args))
            except OSError:
                raise HapticTimelineError("the play process ended unexpectedly") from None
            self._sent = project

    def warm(self, project: Project, start: float, sent: Callable[[], None] | None = None) -> None:
        """Send `project` and wait until the child has loaded what playing it from `start`
        needs (the first chunk rendered, every compiled loop its clips use loaded); `sent` is
        called once the project has crossed, before that wait."""
        with self._warming:
            self.send("warm", project, start)
            if sent is not None:
                sent()
            if self._warmed.poll(START_SECONDS):
                with suppress(EOFError, OSError):
                    self._warmed.recv()

    def stop(self) -> None:
        with self._sending, suppress(OSError, ValueError):  # not amid a warm-up's send
            self._to_child.send(("stop",))

    def _newest(self, message: tuple) -> tuple | None:
        """`message` without its play's number if it is the newest play's, else None (a play
        the host stopped waiting for, such as a USB play still playing out its queue)."""
        number, *rest = message
        return tuple(rest) if number == self._plays else None

    def take(self) -> list[tuple]:
        """The newest play's messages the child has sent so far."""
        out = []
        while True:
            try:
                message = self._from_child.get_nowait()
            except (queue.Empty, OSError, ValueError):
                return out
            if (newest := self._newest(message)) is not None:
                out.append(newest)

    def wait_done(self, timeout: float) -> list[tuple]:
        """The newest play's messages up to its ("done", ...), waiting at most `timeout` s."""
        out = []
        end = time.perf_counter() + timeout
        while True:
            try:
                message = self._from_child.get(timeout=max(0.0, end - time.perf_counter()))
            except (queue.Empty, OSError, ValueError):
                return out
            if (newest := self._newest(message)) is not None:
                out.append(newest)
                if newest[0] == "done":
                    return out

    def close(self) -> None:
        """Ask the child to go; make sure it went."""
        end_child(self.process, self._to_child, self._warmed)
        self._from_child.close()
        self._from_child.cancel_join_thread()


@dataclass
class HeardMeter:
    """A play process's late-block counts as it last sent them (read as a LatenessMeter is)."""

    heard: Lateness

    def counts(self) -> Lateness:
        return self.heard


class RemoteStream:
    """The editor's handle on a stream playing in the play process, its one record there: what
    it plays (start, stop, rate), the newest project version, and where the child's stream is
    and its late-block counts as the child last said (`heard`). `set_project` sends the edit."""

    def __init__(
        self,
        process: PlayProcess,
        project: Project,
        rate: float,
        start: float,
        stop: float,
        tracks: Iterable[str] | None,
        lead: float,
    ) -> None:
        self.process, self.rate, self.start, self.stop = process, rate, start, stop
        self.tracks = None if tracks is None else list(tracks)
        self.state = StreamState(position=start)
        self.lateness = HeardMeter(Lateness(lead=lead))
        self._project = project  # the newest state sent: what the child plays from its next block

    def heard(self, position: float, live_version: int, counts: Lateness) -> None:
        """What the child said of its stream: where it is, the version it plays, its counts."""
        state = self.state
        state.position = position
        if state.live_version != live_version:
            state.live_version, state.live_at = live_version, time.perf_counter()
        self.lateness.heard = counts

    def set_project(self, project: Project) -> int:
        """Send the child a new project state to play from its next block; its version."""
        self._project = project
        self.state.version += 1
        self.process.send("edit", project, self.state.version)
        return self.state.version

    def render(self, project: Project, t0: float, t1: float) -> CoefficientBlock:
        """The coefficients the child renders for `project` on [t0, t1), rendered here."""
        return LiveStream(project, self.rate, t0, t1, tracks=self.tracks).render(project, t0, t1)


class ChildDevice(Device):
    """The editor's handle on a device only the play process opens (the USB knob: one owner of
    the hardware): what it declared, and no play of its own here."""

    def __init__(self, process: PlayProcess) -> None:
        self.process = process

    @property
    def info(self) -> DeviceInfo:
        return self.process.info

    def play(self, program: Any, hand: Any = None, progress: Any = None, monitor: Any = None):
        """Refused: this device plays time projects, from the play process only."""
        raise DeviceError(
            f"the {self.process.device_name} device plays time-mode projects, from the editor's "
            "play process; play a position-mode project on the sim device"
        )


def serve(inbox: Connection, outbox: Any, warmed: Connection, device_name: str) -> None:
    """The child: open and warm the device, then play, edit and stop as the host asks."""
    sys.setswitchinterval(SWITCH_SECONDS)
    try:
        device = open_device(device_name)
        device.warm_up()
    except HapticTimelineError as exc:
        outbox.put((0, "error", str(exc)))
        return
    except Exception as exc:  # noqa: BLE001 - the host must hear why, not wait for a timeout
        outbox.put((0, "error", unexpected("Opening the device", exc)))
        return
    # From here this thread, and every thread it starts (the queue's feeder, each play's, their
    # chunk-ahead workers), run ahead of ordinary programs where permitted: an ordinary one
    # holding the interpreter lock when preempted would make the playing thread wait with it.
    prefer_real_time()
    outbox.put((0, "ready", device.info))
    mixer = Mixer(cache_bytes=256 * 2**20)
    project: Project | None = None
    play: _Play | None = None
    try:
        while True:
            kind, *args = inbox.recv()
            if kind in ("warm", "play", "edit"):
                project = rebuild(project, args[0])
                gc.freeze()  # the project's objects: no collection need walk them while playing
            if kind == "warm" and project is not None:
                if play is None or not play.thread.is_alive():  # else the mixer is the play's
                    with ordinary():  # seconds of renders at 20,000 clips
                        warm_up(device.info.rate, mixer, project, args[1])
                warmed.send(True)
            elif kind == "play" and project is not None:
                if play is not None:
                    play.end()
                play = _Play(device, mixer, project, outbox, *args[1:])
            elif kind == "edit" and play is not None and project is not None:
                play.stream.set_project(project)
                play.stream.state.version = args[1]
            elif kind == "stop" and play is not None:
                play.end()
                play = None
            elif kind == "close":
                break
    except (EOFError, OSError):
        pass  # the host went away
    finally:
        if play is not None:
            play.end()
        device.close()
        outbox.cancel_join_thread()  # a host gone need not read what is left: exit anyway


def warm_up(rate: float, mixer: Mixer, project: Project, start: float) -> None:
    """Render into `mixer` the chunk a play from `start` begins with, then one clip of each sort
    the project holds (kind, tile, fades, direction, stretch mode): the first use of a compiled
    loop loads it holding the interpreter lock for up to 0.3 s, which the playing thread would
    wait for (2.1 s for the 180 sorts of the 20,000-clip benchmark project, load 8)."""
    if project.axis != "time" or project.duration <= start:
        return
    stop = min(project.duration, start + CHUNK_SECONDS)
    stream = LiveStream(project, rate, start, stop, mixer=mixer)
    stream.render(project, start, stop)
    sorts = {}
    for track in project.tracks:
        for c in track.clips:
            key = (track.kind, c.tile_id, c.fade_in.shape, c.fade_out.shape, c.reverse)
            sorts.setdefault((*key, c.stretch_mode), c)
    for clip in sorts.values():
        stream.render(project, clip.start, clip.end)


class _Play:
    """One stream playing on the child's device, on a thread of its own."""

    def __init__(
        self,
        device: Any,
        mixer: Mixer,
        project: Project,
        outbox: Any,
        start: float,
        stop: float,
        loop: bool,
        tracks: Iterable[str] | None,
        hand: Hand,
        asked: float,
        number: int,
    ) -> None:
        info = device.info
        self.number = number  # the host's number for this play, on each of its messages
        self.stream = LiveStream(
            project, info.rate, start, stop, loop, tracks, mixer=mixer, asked=asked, lead=info.lead
        )
        self.outbox = outbox
        self.stream.on_block = self._at
        self.thread = threading.Thread(
            target=self._run, args=(device, hand), daemon=True, name="play"
        )
        self.thread.start()

    def _at(self, state) -> None:
        counts = self.stream.lateness.counts()
        self.outbox.put((self.number, "at", state.position, state.live_version, counts))

    def _part(self, part: LiveTelemetry) -> None:
        if len(part):
            self.outbox.put((self.number, "part", part))

    def _run(self, device: Any, hand: Hand) -> None:
        try:
            device.play(self.stream, hand, monitor=self._part)
            outcome = ""
        except HapticTimelineError as exc:
            outcome = str(exc)
        except Exception as exc:  # noqa: BLE001 - a bug must still end the play, and say so
            outcome = unexpected("Playing", exc)
        self.outbox.put((self.number, "done", outcome, self.stream.lateness.counts()))

    def end(self) -> None:
        """Stop the stream after its block and wait until the thread has said it is done, so
        the next play's messages follow this one's "done" (the host counts on that)."""
        self.stream.stop_stream()
        self.thread.join(timeout=END_SECONDS)
