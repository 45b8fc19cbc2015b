"""Play the project on a device in a worker thread, follow edits live, report telemetry.

Time projects stream through LiveStream, so an edit is felt at the next block. Position projects
play their tables (LiveTables) with the chosen hand: a turning hand sweeps to the table's end,
any other hand plays until Stop (HOLD_SECONDS at most). An edit rebuilds the tables and the sim
plays them from its next 50 ms chunk; the playhead and the scope follow the knob's table angle.
The sim simulates a sweep faster than real time, so the player holds each chunk's telemetry
until its time has come (and stops the sweep there).

The stream counts blocks handed over later than the lead (what a real knob feels as an
underrun); the player names them in a notice while playing and when the play ends. Once the
window has painted, `warm_up` loads the device's compiled code and renders the first chunk
ahead on a background thread, so the first block goes out within a few ms of Play; when the
window's project is replaced (open, new, recover), `project_replaced` warms up on the new one.

A time project on the sim or the USB knob plays from a process of its own (play_process), one
for the editor's process, so the GUI's hold on the interpreter lock cannot delay a block. The USB
knob is opened there only (`device` is then a ChildDevice: its declared info), so the hardware
has one owner. `stream` is then a RemoteStream, the play's one record here (its project
versions, where the child's stream is, its late-block counts), and edits cross to the child as
deltas of the tracks and tiles that changed. The warm-up thread is what hands the child a whole
project (4.2 MB, 0.87 s at 20,000 clips at load 7), so a Play sends only a delta; a sim Play
pressed while that hand-over is still in flight waits HANDOVER_WAIT for it and then plays in
the editor's process instead (the path of the other devices); a USB Play waits for it.
"""

from __future__ import annotations

import atexit
import importlib
import sys
import threading
import time
from collections import deque
from collections.abc import Callable, Iterable
from typing import TYPE_CHECKING

import numpy as np
from PySide6.QtCore import QCoreApplication, QEvent, QObject, QTimer, Signal

from timeline.errors import HapticTimelineError
from timeline.model import Project
from timeline.plugins import discovery
from timeline.plugins.device_protocol import Hand
from timeline.rendering.mixer import Mixer
from timeline.rendering.sound_out import SoundOut

from .job_errors import unexpected

if TYPE_CHECKING:  # the play process's module (and multiprocessing) loads with its first start
    from timeline.plugins.device_protocol import Device, Lateness, LiveTelemetry

    from .live_stream import LiveStream, LiveTables  # with the warm-up, after the first paint
    from .play_process import PlayProcess, RemoteStream

HOLD_SECONDS = 600.0  # a position project played without turning plays this long unless stopped
LATE_NOTICE_SECONDS = 1.0  # while playing, late blocks are named at most this often
# While playing, a thread busy in Python (the GUI's) hands the interpreter lock over after this
# long instead of CPython's 5 ms, so the playing thread, which needs it for a moment every
# 10 ms block, waits less for it.
SWITCH_SECONDS = 0.001
OWN_PROCESS = ("sim", "usb")  # devices whose time plays run in the play process
# Devices opened in the play process only (ChildDevice here): the USB knob, whose hardware has one
# owner, and whose blocks must not depend on this process's interpreter lock.
CHILD_ONLY = ("usb",)
IDLE_SECONDS = 0.5  # the first warm-up waits for this long without input after the first paint
_INPUT = frozenset(
    (QEvent.Type.MouseButtonPress, QEvent.Type.MouseMove, QEvent.Type.KeyPress, QEvent.Type.Wheel)
)
STOP_SECONDS = 2.0  # a play stopped in the play process is given up on if not ended by then
HANDOVER_WAIT = 0.005  # a Play waits this long (GUI thread) for the warm-up's hand-over


class _Shared:
    """The play process of the editor's process (started at the first warm-up or play, kept
    for every window, ended when the application quits or at exit) and the player whose play
    it is playing."""

    lock = threading.Lock()
    process: PlayProcess | None = None
    owner: Player | None = None
    ending = False  # `close` is connected to the application's quit

    @classmethod
    def end_with(cls, app: QCoreApplication | None) -> None:
        """End the play process when `app` quits (its last window closed)."""
        if app is not None and not cls.ending:
            app.aboutToQuit.connect(cls.close)
            cls.ending = True

    @classmethod
    def close(cls) -> None:
        """End the play process, waiting until it has gone."""
        with cls.lock:
            if cls.process is not None:
                cls.process.close()
                cls.process = None
            cls.owner = None

    @classmethod
    def get(cls, device_name: str) -> PlayProcess:
        with cls.lock:
            if cls.process is not None and (
                not cls.process.alive or cls.process.device_name != device_name
            ):
                cls.process.close()
                cls.process = None
            if cls.process is None:
                from .play_process import PlayProcess

                cls.process = PlayProcess(device_name)
                atexit.register(cls.process.close)
            return cls.process


class _Stopped(Exception):
    """Stop was pressed during a position sweep (control flow, not a user error)."""


class Player(QObject):
    """Opens the chosen device plugin and plays the document's project on it.

    The playing thread never touches Qt: it leaves telemetry in a queue that a GUI-thread timer
    drains (the Friture pattern), and the signals below are emitted from that timer.
    """

    telemetry = Signal(object, object)  # angle (rad; table angle in position mode), torque (N*m)
    position = Signal(float)
    finished = Signal(str)  # "" or an error sentence
    notice = Signal(str)  # something the user should know that does not stop playing

    def __init__(self, parent: QObject | None = None) -> None:
        super().__init__(parent)
        self.device_name = "sim"
        self.device: Device | None = None
        # The time play's stream: here, or its handle in the play process (its one record here)
        self.stream: LiveStream | RemoteStream | None = None
        self.tables: LiveTables | None = None
        self.hand = Hand("hold")
        self._thread: threading.Thread | None = None
        self._halt = threading.Event()
        self._started = 0.0
        self._parts: deque[LiveTelemetry] = deque(maxlen=200)
        self._position: float | None = None
        self._outcome: str | None = None
        self._origin = 0.0  # table angle where a position play started (telemetry is relative)
        self._angle: float | None = None  # newest table angle of a position play
        self._poll = QTimer(self)
        self._poll.setInterval(33)
        self._poll.timeout.connect(self._drain)
        self.sound = SoundOut()  # the source sound (audio tracks) heard with the haptics
        self._mixer = Mixer(cache_bytes=256 * 2**20)  # kept between plays, warmed ahead
        self._opening = threading.Lock()
        self._warm: threading.Thread | None = None
        self._warm_lock = threading.Lock()  # guards `_warm_next` and the thread's start and end
        self._warm_next: tuple[Project, float] | None = None  # the next project to warm up on
        self._warm_running = False  # the warm-up thread has not yet taken its last job
        self._handed = threading.Event()  # set: no project is waiting to cross to the child
        self._handed.set()
        self._warm_source: Callable[[], Project] | None = None  # until the first warm-up
        self._idle: QTimer | None = None  # after the first paint: fires once input has paused
        self._app = QCoreApplication.instance()
        self._late_named = (0, 0.0)  # late blocks already named, and when
        self._switch = 0.0  # the interpreter's switch interval before playing (0: not playing)
        self._opened: Device | None = None  # the device this player opened itself
        self._remote: PlayProcess | None = None  # the play process, while it plays for us
        self._ending: PlayProcess | None = None  # it ends a play we stopped: its "done" is due
        self._stopped_at = 0.0  # perf_counter of that stop
        _Shared.end_with(QCoreApplication.instance())

    @staticmethod
    def devices() -> list[str]:
        """Device plugins' names as their entry points register them, none loaded: the sim's
        compiled loop (numba) is not imported before the window's first paint; a plugin that
        cannot load says so when chosen (open_device)."""
        return sorted(discovery.names(discovery.DEVICES))

    @property
    def playing(self) -> bool:
        if self._remote is not None:
            return True
        return self._thread is not None and self._thread.is_alive()

    def choose_device(self, name: str) -> None:
        """Use another device from the next Play on."""
        self.stop()
        with self._opening:  # not while a warm-up opens the old one
            if self.device is not None:
                self.device.close()
                self.device = None
            self.device_name = name

    def _open(self) -> Device:
        with self._opening:
            if self.device is None:
                if self.device_name in CHILD_ONLY:
                    from .play_process import ChildDevice

                    opened: Device = ChildDevice(_Shared.get(self.device_name))
                else:
                    from timeline.plugins.device_protocol import open_device

                    opened = open_device(self.device_name)
                self.device = self._opened = opened
            return self.device

    def _own_process(self, device: Device, project: Project) -> bool:
        """Whether a play of `project` on `device` runs in the play process."""
        return project.axis == "time" and self.device_name in OWN_PROCESS and device is self._opened

    def warm_up_once_painted(self, window: QObject, project: Callable[[], Project]) -> None:
        """Warm up (below) on the project of the moment once `window` has painted and the editor
        has then had no input for IDLE_SECONDS, so the warm-up (which starts the play process)
        never delays the first paint nor competes with the designer's first gestures. A Play
        or a project replaced before that starts it at once."""
        self._warm_source = project
        window.installEventFilter(self)

    def eventFilter(self, watched: QObject, event: QEvent) -> bool:
        kind = event.type()
        if kind == QEvent.Type.Paint and watched is not self._app and self._idle is None:
            watched.removeEventFilter(self)
            self._idle = QTimer(self)
            self._idle.setSingleShot(True)
            self._idle.setInterval(round(IDLE_SECONDS * 1000))
            self._idle.timeout.connect(self._warm_when_idle)
            if self._app is not None:
                self._app.installEventFilter(self)  # only until the warm-up starts
            self._idle.start()
        elif kind in _INPUT and self._idle is not None and self._warm_source is not None:
            self._idle.start()  # input: not idle yet, wait again
        return False

    def _warm_when_idle(self) -> None:
        """The first warm-up, on the window's project of the moment (if none has started)."""
        source, self._warm_source = self._warm_source, None
        if self._app is not None:
            self._app.removeEventFilter(self)
        if source is not None:
            self.warm_up(source())

    def warm_up(self, project: Project, start: float = 0.0) -> None:
        """On a background thread: open the device, hand the project to the play process,
        load its compiled code and render the project's first chunk from `start` into the mixer
        kept for the next play. Called again while that runs, it warms up on the newest
        project once the running one is done."""
        if self._warm_source is not None:  # the first warm-up: no need to wait for idle now
            self._warm_source = None
            if self._app is not None:
                self._app.removeEventFilter(self)
            if self._idle is not None:
                self._idle.stop()
        with self._warm_lock:
            self._handed.clear()
            self._warm_next = (project, start)
            if not self._warm_running:
                self._warm_running = True
                self._warm = threading.Thread(
                    target=self._warming, daemon=True, name="player warm-up"
                )
                self._warm.start()

    def project_replaced(self, project: Project) -> None:
        """The window holds another project (open, new, recover): hand it to the play process
        in the background, so the next Play sends only what changed since."""
        self.stop()
        self.warm_up(project)

    def _warming(self) -> None:
        """The warm-up thread: warm up on each project asked for, the newest first."""
        while True:
            with self._warm_lock:
                job, self._warm_next = self._warm_next, None
                if job is None:
                    self._warm_running = False
                    self._handed.set()
                    return
            self._warm_up(*job)

    def _sent(self) -> None:
        """The warm-up's project has crossed to the child: Play may send a delta against it
        (unless a newer project waits to cross)."""
        with self._warm_lock:
            if self._warm_next is None:
                self._handed.set()

    def _warm_up(self, project: Project, start: float) -> None:
        from .live_stream import CHUNK_SECONDS, LiveStream

        try:
            device = self._open()
            if self._own_process(device, project):
                _Shared.get(self.device_name).warm(project, start, self._sent)
            self._sent()
            device.warm_up()  # position plays still run here
            # The findings check's libraries (scipy.signal), imported here rather than beside
            # the first play, where the import would hold the interpreter lock for ~0.1 s.
            importlib.import_module("timeline.limits.check")
            if project.axis == "time" and project.duration > start and device is not self._opened:
                stop = min(project.duration, start + CHUNK_SECONDS)
                stream = LiveStream(project, device.info.rate, start, stop, mixer=self._mixer)
                stream.render(project, start, stop)
        except Exception:  # noqa: BLE001 - a failed warm-up costs only time: Play says why
            return

    @property
    def lateness(self) -> Lateness | None:
        """Late blocks of the current (or last) time-mode play; None for a position play."""
        if self.stream is None:
            return None
        return self.stream.lateness.counts()

    def play(
        self,
        project: Project,
        start: float = 0.0,
        stop: float | None = None,
        loop: bool = False,
        tracks: Iterable[str] | None = None,
        origin: float | None = None,
    ) -> None:
        """Start playing (stops a play already running); errors come back through `finished`.

        `origin` (rad) is where the knob starts in a position project (its first rest point
        by default).
        """
        from timeline.rendering import playback

        from .live_stream import LiveStream, LiveTables

        self.stop()
        self._ending = None  # a stopped play's end is superseded (its "done" is not this one's)
        asked = time.perf_counter()
        if self._warm_source is not None:  # Play before the editor was idle: warm up now
            self.warm_up(project, start)
        try:
            device = self._open()
            self.stream = self.tables = None
            stop = project.duration if stop is None else stop
            if project.axis == "position":
                hand = self.hand
                duration = None if hand.turn_speed else HOLD_SECONDS
                sweep, _ = playback.position_program(project, duration, hand, origin)
                self.tables = LiveTables(sweep)
                program, self._origin = self.tables.program, sweep.origin
            else:
                if stop <= start:
                    raise HapticTimelineError("nothing to play: the project has no clips there")
                info = device.info
                if self._own_process(device, project) and self._handed.wait(
                    None if self.device_name in CHILD_ONLY else HANDOVER_WAIT
                ):  # a device the child alone holds waits for the hand-over, however long
                    self.stream = self._play_there(project, start, stop, loop, tracks, asked)
                else:
                    warming = self._warm is not None and self._warm.is_alive()
                    mixer = None if warming else self._mixer  # one thread per mixer at a time
                    self.stream = LiveStream(
                        project, info.rate, start, stop, loop, tracks, mixer=mixer, asked=asked,
                        lead=info.lead,
                    )  # fmt: skip
                    self.stream.on_block = self._at
                    program, hand = self.stream, self.hand
        except HapticTimelineError as exc:
            self.finished.emit(str(exc))
            return
        self._outcome = None
        self._late_named = (0, 0.0)
        self._halt.clear()
        self._started = time.perf_counter()
        self._switch = self._switch or sys.getswitchinterval()
        sys.setswitchinterval(SWITCH_SECONDS)
        if self._remote is None:
            self._thread = threading.Thread(
                target=self._run, args=(device, program, hand), daemon=True
            )
            self._thread.start()
        self._poll.start()
        if self.stream is not None:
            note = self.sound.play(project, start, stop, loop)
            if note:
                self.notice.emit(note)

    def _play_there(
        self,
        project: Project,
        start: float,
        stop: float,
        loop: bool,
        tracks: Iterable[str] | None,
        asked: float,
    ) -> RemoteStream:
        """Play the stream in the play process; its handle here."""
        from .play_process import RemoteStream

        process = _Shared.get(self.device_name)
        owner = _Shared.owner
        if owner is not None and owner is not self:
            owner.stop()  # another window's play: one knob plays one thing
        info = process.info
        stream = RemoteStream(process, project, info.rate, start, stop, tracks, info.lead)
        process.send("play", project, start, stop, loop, tracks, self.hand, asked)
        self._remote, _Shared.owner = process, self
        return stream

    def _heard(self, messages: list[tuple]) -> None:
        """Take in what the play process said: telemetry, where it is, late counts, the end."""
        from .play_process import RemoteStream  # loaded: the play process is speaking

        stream = self.stream
        for kind, *args in messages:
            if kind == "part":
                self._parts.append(args[0])
            elif kind == "at" and isinstance(stream, RemoteStream):
                stream.heard(*args)
                self._position = args[0]
            elif kind == "done":
                self._ended(*args)
                self._remote = None

    def _heard_end(self, messages: list[tuple]) -> None:
        """Take in a stopped play's end: its final late counts and outcome (what it played
        after the Stop is not shown); given up on after STOP_SECONDS."""
        for kind, *args in messages:
            if kind == "done":
                self._ended(*args)
                self._ending = None
                return
        if time.perf_counter() - self._stopped_at > STOP_SECONDS:
            self._outcome, self._ending = "", None  # no answer: the next play starts it over

    def _ended(self, outcome: str, late: Lateness) -> None:
        """The play process's "done": how the play ended and its final late counts."""
        from .play_process import RemoteStream  # loaded: the play process is speaking

        if isinstance(self.stream, RemoteStream):
            self.stream.lateness.heard = late
        self._outcome = outcome

    def _run(self, device: Device, program, hand: Hand) -> None:
        try:
            device.play(program, hand, monitor=self._part)
        except _Stopped:
            pass
        except HapticTimelineError as exc:
            self._outcome = str(exc)
            return
        except Exception as exc:  # noqa: BLE001 - a bug must still end the play, and say so
            self._outcome = unexpected("Playing", exc)
            return
        self._outcome = ""

    def _at(self, state) -> None:
        self._position = state.position

    def _part(self, part: LiveTelemetry) -> None:
        if len(part) and self.tables is not None:
            from timeline.plugins.device_protocol import LiveTelemetry

            part = LiveTelemetry(part.time, self._origin + part.angle, part.torque)
            self._position = float(part.angle[-1])
        if len(part):
            self._parts.append(part)
        if self.tables is not None and len(part):
            self._halt.wait(self._started + float(part.time[-1]) - time.perf_counter())
            if self._halt.is_set():
                raise _Stopped("stopped")

    def _drain(self) -> None:
        """GUI thread: pass on what the playing thread (or process) left behind."""
        if self._remote is not None:
            self._heard(self._remote.take())
        elif self._ending is not None:
            self._heard_end(self._ending.take())
        parts = [self._parts.popleft() for _ in range(len(self._parts))]
        if parts:
            angle = np.concatenate([p.angle for p in parts])
            torque = np.concatenate([p.torque for p in parts])
            self.telemetry.emit(angle, torque)
        if self._position is not None:
            if self.tables is not None:
                self._angle = self._position
            self.position.emit(self._position)
            self._position = None
        ended = self._outcome is not None and not self.playing
        late = self._late_sentence(ended)
        if ended:
            outcome, self._outcome = self._outcome or "", None
            self._restore_switch()
            self._poll.stop()
            self.sound.stop()
            if late and outcome:
                outcome = f"{outcome}; {late}"
            elif late:
                self.notice.emit(late)
            self.finished.emit(outcome)
        elif late:
            self.notice.emit(late)

    def _restore_switch(self) -> None:
        if self._switch:
            sys.setswitchinterval(self._switch)
            self._switch = 0.0

    def _late_sentence(self, ended: bool) -> str:
        """The late blocks to name now: new ones (at most once a second), or all at the end."""
        counts = self.lateness
        if counts is None or not counts.late:
            return ""
        named, when = self._late_named
        now = time.perf_counter()
        if not ended and (counts.late == named or now - when < LATE_NOTICE_SECONDS):
            return ""
        self._late_named = (counts.late, now)
        return counts.sentence()

    @property
    def angle(self) -> float | None:
        """The knob's newest table angle (rad) while a position project plays."""
        return self._angle if self.tables is not None else None

    def follow(self, project: Project) -> None:
        """Hand a new project state to the running stream (edit-to-feel starts here)."""
        if not self.playing:
            return
        if self.stream is not None:
            self.stream.set_project(project)  # a RemoteStream sends it to the play process
            self.sound.follow(project)
        elif self.tables is not None:
            self.tables.set_project(project)

    def stop(self) -> None:
        """Stop playing; where it got to is not reported after this (the playhead stays where a
        stop or a scrub left it). A play in the play process is asked to stop and not waited
        for (a USB play's end takes ~0.15 s: its queue plays out, then the knob ramps to zero);
        `finished` follows its end, through the poll timer. A thread playing here is waited
        for (its block)."""
        self._halt.set()
        self.sound.stop()
        if self.stream is not None:  # (the live stream's module loads with the first stream)
            from .live_stream import LiveStream

            if isinstance(self.stream, LiveStream):
                self.stream.stop_stream()
        if self._remote is not None:  # still playing in the play process
            self._remote.stop()
            self._ending, self._stopped_at, self._remote = self._remote, time.perf_counter(), None
        if self._thread is not None:
            self._thread.join(timeout=2.0)
            self._thread = None
        self._position = None

    def close(self) -> None:
        """Stop, release the device and report nothing more (the window is closing)."""
        self.stop()
        self._ending = None
        if _Shared.owner is self:
            _Shared.owner = None
        self._poll.stop()
        self._restore_switch()
        if self.device is not None:
            self.device.close()
            self.device = None
