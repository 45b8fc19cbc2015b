"""What the editor costs the GUI thread: zoom, repaint, a clip drag, the stale limits checks a
slow drag leaves, and launch to the first paint.

The editor runs offscreen in child processes (python -m timeline.bench.editor measure|launch), so
the benchmark's own imports do not count and each run starts cold. GUI CPU is the main thread's
CPU time (time.thread_time): the findings worker's checks run beside it and are not counted;
launch is wall time from spawning the process to the end of the window's first paint, and the
process's CPU time by then.
"""

from __future__ import annotations

import importlib.util
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from timeline.bench.report import Table

NAME = "editor"
SUMMARY = "editor GUI CPU per zoom step, repaint and drag move at 20k clips; launch to first paint"
EXAMPLE = Path(__file__).resolve().parents[2] / "projects" / "fan_knob.htl"
HEAVY = ("scipy.signal", "numba", "matplotlib")
ZOOM_STEPS = 14  # from fit, each 1.25x: 2 px/s to 45 px/s on the 600 s project
DRAG_MOVES = 30
PAUSES = 8  # pauses over the check's 250 ms delay in the slow drag
PAUSE_S = 0.4
LAUNCHES = 10  # of the editor and of the bare window, interleaved


def run(quick: bool, out: Path) -> list[Table]:
    if importlib.util.find_spec("PySide6") is None:
        skipped = Table("Editor GUI CPU", ["result"], [["skipped: PySide6 is not installed"]])
        return [skipped]
    load = os.getloadavg()[0]
    clips = 2_000 if quick else 20_000
    found = _child("measure", str(clips), "quick" if quick else "full")
    gui = Table(
        f"Editor GUI CPU at {clips:,} clips (offscreen, main thread CPU time, load {load:.1f})",
        ["what", "median ms", "max ms", "target ms", "count"],
    )
    for what, key, target in (
        ("repaint at fit", "repaint", 16),
        ("zoom step (zoom + repaint), fit to 45 px/s and back", "zoom", 16),
        ("clip drag, per mouse move (edit, lanes, editor, inspector)", "drag", 8),
    ):
        values = found[key]
        gui.rows.append(
            [what, f"{statistics.median(values):.1f}", f"{max(values):.1f}", target, len(values)]
        )
    checks = found["checks"]
    pauses = 2 if quick else PAUSES
    stale = Table(
        f"Limits checks in a slow drag ({pauses} pauses of {PAUSE_S:g} s, {clips:,} clips)",
        ["started", "finished", "cancelled", "stale running at release",
         "all stale stopped after ms (wall)", "stale 1 s later"],
        [[checks["started"], checks["finished"], checks["cancelled"], checks["stale_at_release"],
          checks["stopped_ms"], checks["stale_after"]]],
    )  # fmt: skip
    stale.notes.append(
        "a drag starts no check until the mouse lets go; the check running as it began stops at "
        "its next step (the longest left: rendering the design, ~2.6 s at 20k clips at load ~10);"
        " queued checks are dropped at once"
    )
    launch = Table(
        f"Launch to first paint (new process, bytecode cached, {LAUNCHES} launches of each "
        f"interleaved with a bare Qt window's, load {load:.1f})",
        ["project", "wall s least / median", "CPU s least / median", "bare Qt window wall s",
         "bare CPU s", "target s", "heavy loaded"],
    )  # fmt: skip
    with tempfile.TemporaryDirectory() as folder:
        projects = [("fan_knob.htl (example)", EXAMPLE, "0.5")]
        if EXAMPLE.exists() and not quick:
            large = Path(folder) / "large.htl"
            _save_large(large, clips)
            projects.append((f"{clips:,} clips", large, "-"))
        for label, path, target in projects:
            if not path.exists():
                launch.rows.append([label, "skipped: not in this installation", "", "", "", target,
                                    ""])  # fmt: skip
                continue
            editor, bare, loaded = _launch(path, LAUNCHES)
            launch.rows.append(
                [label, *(_least_median(editor[k]) for k in ("wall", "cpu")),
                 *(_least_median(bare[k]) for k in ("wall", "cpu")), target,
                 ", ".join(loaded) or "none"]
            )  # fmt: skip
    launch.notes.append(
        "target 0.5 s wall for an example, at load ~2; CPU is the process's CPU time at the end "
        "of the first paint; the bare window (PySide6 import, QApplication, one widget's first "
        "paint) is the floor any Qt editor pays on this machine"
    )
    return [gui, stale, launch]


def _save_large(path: Path, clips: int) -> None:
    from timeline.bench.scenes import QUICK, LargeSpec, large_project
    from timeline.files import projectfile

    spec = QUICK if clips < 20_000 else LargeSpec()
    projectfile.save(large_project(spec), path)


def _env() -> dict[str, str]:
    return {**os.environ, "QT_QPA_PLATFORM": "offscreen"}


def _child(*argv: str, env: dict[str, str] | None = None) -> dict:
    """Run this module in a child process; its last stdout line is JSON."""
    done = subprocess.run(
        [sys.executable, "-m", "timeline.bench.editor", *argv],
        capture_output=True,
        text=True,
        env=env or _env(),
        check=False,
    )
    if done.returncode != 0:
        raise RuntimeError(f"editor bench child failed: {done.stderr.strip()[-2000:]}")
    return json.loads(done.stdout.strip().splitlines()[-1])


def _launch(path: Path, repeat: int) -> tuple[dict, dict, list[str]]:
    """Wall seconds from spawning the editor on `path` to its first paint and the process's CPU
    seconds by then, `repeat` launches, each followed by a bare Qt window's, with the bytecode
    cached as on a user's second run (in a temporary folder: PYTHONDONTWRITEBYTECODE, if set,
    would make every run compile)."""
    editor: dict[str, list[float]] = {"wall": [], "cpu": []}
    bare: dict[str, list[float]] = {"wall": [], "cpu": []}
    loaded: list[str] = []
    with tempfile.TemporaryDirectory() as home:
        env = {k: v for k, v in _env().items() if k != "PYTHONDONTWRITEBYTECODE"}
        env["PYTHONPYCACHEPREFIX"] = os.path.join(home, "bytecode")
        _child("launch", str(path), home, env=env)  # writes the bytecode
        _child("bare", "", home, env=env)
        for _ in range(repeat):
            for argv, into in ((("launch", str(path), home), editor), (("bare", "", home), bare)):
                start = time.perf_counter()  # CLOCK_MONOTONIC: the child reads the same clock
                found = _child(*argv, env=env)
                into["wall"].append(found["painted"] - start)
                into["cpu"].append(found["cpu"])
                loaded = found.get("loaded", loaded)
    return editor, bare, loaded


def _least_median(values: list[float]) -> str:
    return f"{min(values):.2f} / {statistics.median(values):.2f}"


# --- child processes ------------------------------------------------------------------------


def _child_launch(path: str, home: str) -> None:
    """Open the editor as `haptic-timeline edit` does; print when its first paint is done."""
    os.environ["XDG_DATA_HOME"] = home  # no autosave of the user's is offered
    # nor the user's window state restored (QSettings): every launch starts from the same one
    os.environ["XDG_CONFIG_HOME"] = home
    from timeline.gui.app import launch  # the first import, as in `haptic-timeline edit`
    from timeline.gui.first_paint import after_first_paint

    app, window = launch(path)

    def painted() -> None:  # right after the lanes' first paint
        loaded = [m for m in HEAVY if m in sys.modules]
        done = {"painted": time.perf_counter(), "cpu": time.process_time(), "loaded": loaded}
        print(json.dumps(done), flush=True)
        window.close()
        app.quit()

    after_first_paint(window.view.viewport(), painted)
    app.exec()


def _child_bare() -> None:
    """A bare Qt window's first paint: the floor under the editor's launch."""
    from PySide6.QtCore import QEvent, QObject, QTimer
    from PySide6.QtWidgets import QApplication, QWidget

    app = QApplication([])
    window = QWidget()
    window.resize(1200, 800)

    def painted() -> None:
        print(json.dumps({"painted": time.perf_counter(), "cpu": time.process_time()}), flush=True)
        app.quit()

    class FirstPaint(QObject):
        def eventFilter(self, watched: QObject, event: QEvent) -> bool:  # noqa: N802
            if event.type() == QEvent.Type.Paint:
                watched.removeEventFilter(self)
                QTimer.singleShot(0, painted)
            return False

    first = FirstPaint()
    window.installEventFilter(first)
    window.show()
    app.exec()


def _child_measure(clips: int, quick: bool) -> None:
    """Zoom, repaint and drag in the editor on a large project; print the GUI CPU of each."""
    os.environ["XDG_DATA_HOME"] = tempfile.mkdtemp()
    from PySide6.QtCore import QPoint, Qt
    from PySide6.QtTest import QTest
    from PySide6.QtWidgets import QApplication

    from timeline.bench.scenes import QUICK, LargeSpec, large_project
    from timeline.gui.main_window import MainWindow

    app = QApplication([])
    win = MainWindow(large_project(QUICK if clips < 20_000 else LargeSpec()))
    win.resize(1400, 860)
    win.show()
    view, viewport = win.view, win.view.viewport()
    view.fit()
    _settle(app, win, 120.0)  # the findings shown: their shading is part of every paint

    def cpu_ms(work) -> float:  # noqa: ANN001
        start = time.thread_time()
        work()
        app.processEvents()
        return 1e3 * (time.thread_time() - start)

    repaint = [cpu_ms(viewport.update) for _ in range(5)]  # painted by processEvents
    zoom = [cpu_ms(lambda: view.zoom(1.25)) for _ in range(ZOOM_STEPS)]
    zoom += [cpu_ms(lambda: view.zoom(0.8)) for _ in range(ZOOM_STEPS)]
    view.lane_geometry.px_per_unit = 40.0
    view.refresh()
    clip = win.doc.project.tracks[0].clips[len(win.doc.project.tracks[0].clips) // 2]
    view.centerOn(view.clip_scene_rect(clip.id).center())
    app.processEvents()
    at = view.mapFromScene(view.clip_scene_rect(clip.id).center())
    left, none = Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier
    QTest.mousePress(viewport, left, none, at)
    app.processEvents()
    drag = [cpu_ms(lambda i=i: QTest.mouseMove(viewport, at + QPoint(2 * i + 2, 0)))
            for i in range(DRAG_MOVES)]  # fmt: skip
    QTest.mouseRelease(viewport, left, none, at + QPoint(2 * DRAG_MOVES, 0))
    _settle(app, win, 120.0)
    checks = _slow_drag(app, win, view, viewport, 2 if quick else PAUSES)
    print(json.dumps({"repaint": repaint, "zoom": zoom, "drag": drag, "checks": checks}))
    win.findings.close()
    win.autosaver.discard()


def _slow_drag(app, win, view, viewport, pauses: int) -> dict[str, int]:  # noqa: ANN001
    """Drag a clip with pauses longer than the check's delay; count the checks."""
    from PySide6.QtCore import QPoint, Qt
    from PySide6.QtTest import QTest

    findings = win.findings
    before = dict(findings.counts)
    clip = win.doc.project.tracks[1].clips[len(win.doc.project.tracks[1].clips) // 2]
    view.centerOn(view.clip_scene_rect(clip.id).center())
    app.processEvents()
    at = view.mapFromScene(view.clip_scene_rect(clip.id).center())
    left, none = Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier
    QTest.mousePress(viewport, left, none, at)
    for i in range(pauses):
        QTest.mouseMove(viewport, at + QPoint(3 * i + 3, 0))
        _wait(app, PAUSE_S)
    QTest.mouseMove(viewport, at + QPoint(3 * pauses + 3, 0))  # the last move makes all stale
    QTest.mouseRelease(viewport, left, none, at + QPoint(3 * pauses + 3, 0))
    stale_at_release = len(findings.stale_running())
    released = time.perf_counter()
    while findings.stale_running() and time.perf_counter() - released < 10.0:
        app.processEvents()
        time.sleep(0.002)
    stopped_ms = 1e3 * (time.perf_counter() - released)
    _wait(app, 1.0)
    counts = {
        k: findings.counts[k] - before.get(k, 0) for k in ("started", "finished", "cancelled")
    }
    return {**counts, "stale_at_release": stale_at_release, "stopped_ms": round(stopped_ms),
            "stale_after": len(findings.stale_running())}  # fmt: skip


def _wait(app, seconds: float) -> None:  # noqa: ANN001
    end = time.perf_counter() + seconds
    while time.perf_counter() < end:
        app.processEvents()
        time.sleep(0.005)


def _settle(app, win, timeout: float) -> None:  # noqa: ANN001
    end = time.perf_counter() + timeout
    while not win.findings.settled and time.perf_counter() < end:
        app.processEvents()
        time.sleep(0.01)


if __name__ == "__main__":
    if sys.argv[1] == "launch":
        _child_launch(sys.argv[2], sys.argv[3])
    elif sys.argv[1] == "bare":
        _child_bare()
    else:
        _child_measure(int(sys.argv[2]), sys.argv[3] == "quick")
