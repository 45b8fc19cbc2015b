"""One editor session for the `playback` benchmark: play while the GUI idles, scrolls, zooms, drags.

Run in its own process (a cold start, as a designer's): `python -m timeline.bench.playback_session
--device sim --clips 20000 --seconds 4 [--hog]`. The editor (offscreen) opens the large
benchmark project, waits for its warm-up, then for each gesture plays the project's first
`seconds` while the gesture runs on the GUI thread, and prints one JSON line: the
stream's late blocks, gaps, worst delay, first-block latency, and how the play ended. With
`--hog` a process spinning on one core runs beside it. For `--device usb` set
HAPTIC_TIMELINE_USB_EMULATE=realtime: the emulated knob then runs on the wall clock.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
from collections.abc import Callable
from dataclasses import asdict, replace

from timeline.bench.machine_stall import MachineStall

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

GESTURES = ("idle", "scroll", "zoom", "drag")
STEP_MS = 16  # one gesture step per frame at 60 Hz
HOG = "while True:\n    pass\n"  # one core busy, as a designer's other programs
STUCK_SECONDS = 30.0  # a play not ended this long after its length is stopped


def main() -> None:
    parser = argparse.ArgumentParser(description="one editor session of `bench playback`")
    parser.add_argument("--device", default="sim")
    parser.add_argument("--clips", type=int, default=20_000)
    parser.add_argument("--seconds", type=float, default=4.0)
    parser.add_argument("--hog", action="store_true")
    parser.add_argument("--gestures", default=",".join(GESTURES))
    parser.add_argument("--alone", action="store_true", help="the play process with no editor")
    args = parser.parse_args()
    hog = subprocess.Popen([sys.executable, "-c", HOG]) if args.hog else None
    try:
        if args.alone:
            rows = [alone(args.device, args.clips, args.seconds)]
        else:
            rows = session(args.device, args.clips, args.seconds, args.gestures.split(","))
        for row in rows:
            print(json.dumps({**row, "priority": granted()}), flush=True)
    finally:
        if hog is not None:
            hog.kill()
            hog.wait()


def session(device: str, clips: int, seconds: float, gestures: list[str]) -> list[dict]:
    """Open the editor on the benchmark project and play once per gesture."""
    from PySide6.QtWidgets import QApplication

    from timeline.bench.scenes import FULL, QUICK, large_project
    from timeline.gui.main_window import MainWindow

    app = QApplication.instance() or QApplication([])
    spec = FULL if clips >= FULL.clips else replace(QUICK, clips=clips)
    win = MainWindow(large_project(spec))
    win.resize(1400, 860)
    win.transport.device.setCurrentText(device)  # before the warm-up opens it
    win.show()
    _wait(app, lambda: win.player._warm is not None, 30.0)
    warm = win.player._warm
    if warm is not None:
        warm.join()
    win.view.lane_geometry.px_per_unit = 200.0
    win.view.refresh()
    app.processEvents()
    rows = [_play(app, win, gesture, seconds) for gesture in gestures]
    win.player.close()
    win.autosaver.discard()
    win.findings.close()
    return rows


def alone(device: str, clips: int, seconds: float) -> dict:
    """The play process with no editor beside it: warmed on the benchmark project as the editor
    warms it, then one play of `seconds` from the start."""
    from timeline.bench.scenes import FULL, QUICK, large_project
    from timeline.gui.play_process import PlayProcess
    from timeline.plugins.device_protocol import Hand

    project = large_project(FULL if clips >= FULL.clips else replace(QUICK, clips=clips))
    process = PlayProcess(device)
    try:
        process.warm(project, 0.0)
        probe = MachineStall()
        probe.start()
        asked = time.perf_counter()
        process.send("play", project, 0.0, seconds, False, None, Hand("hold"), asked)
        done = process.wait_done(seconds + 30.0)[-1]
        stalled = probe.stop()
    finally:
        process.close()
    return {"gesture": "child alone", **asdict(done[2]), "ended": done[1], "stalled": stalled,
            "load": os.getloadavg()[0]}  # fmt: skip


def granted() -> str:
    """The priority the play process's playing thread gets (prefer_real_time, tried on a
    thread of this process, which the play process inherits its permissions from)."""
    import threading

    from timeline.plugins.device_protocol.child_process import prefer_real_time

    got: list[str] = []
    thread = threading.Thread(target=lambda: got.append(prefer_real_time()))
    thread.start()
    thread.join()
    return got[0] or "normal"


def _play(app, win, gesture: str, seconds: float) -> dict:
    """Play [0, seconds) of the project while the gesture runs; the stream's counts afterwards.

    The play's end is the stream's (its stop time), not a Stop from the GUI thread: a GUI thread
    stalled past the play's length (the findings overlay settling at 20,000 clips: 1.6-1.7 s)
    would have stopped it late, and the row counted the extra blocks (520 in a "4 s" play).
    """
    win.view.scene().set_cursor(0.0)
    said: dict[str, list[str]] = {"notice": [], "finished": []}
    win.player.notice.connect(said["notice"].append)
    win.player.finished.connect(said["finished"].append)
    win.transport.scope.clear()
    probe = MachineStall()
    probe.start()
    win.player.play(win.doc.project, 0.0, seconds)
    win.transport.show_playing(win.player.playing)
    step, finish = _gesture(win, gesture)
    end = time.perf_counter() + seconds + STUCK_SECONDS
    while win.player.playing and time.perf_counter() < end:
        step()
        _pump(app, STEP_MS / 1000)
    finish()
    stalled = probe.stop()
    stuck = win.player.playing
    if stuck:
        win.play_stop()
    _wait(app, lambda: bool(said["finished"]), 5.0)
    win.player.notice.disconnect(said["notice"].append)
    win.player.finished.disconnect(said["finished"].append)
    counts = win.player.lateness
    return {
        "gesture": gesture,
        **(asdict(counts) if counts else {}),
        "ended": "did not end by itself" if stuck else "".join(said["finished"]),
        "named": next((t for t in reversed(said["notice"] + said["finished"]) if "late" in t), ""),
        "stalled": stalled,
        "load": os.getloadavg()[0],
    }


def _gesture(win, gesture: str) -> tuple[Callable[[], None], Callable[[], None]]:
    """One step of the gesture (called once a frame), and what ends it."""
    from PySide6.QtCore import QPoint, QPointF, Qt
    from PySide6.QtTest import QTest

    view = win.view
    if gesture == "scroll":
        bar = view.horizontalScrollBar()
        return lambda: bar.setValue(bar.value() + 40 if bar.value() < bar.maximum() else 0), _none
    if gesture == "zoom":
        steps = [0]

        def zoom() -> None:  # in and out by turns
            steps[0] += 1
            view.zoom(1.25 if steps[0] % 2 else 0.8)

        return zoom, _none
    if gesture == "drag":
        track = win.doc.project.tracks[0]
        clip = min(track.clips, key=lambda c: abs(c.start - 1.0))
        rect = view.clip_scene_rect(clip.id)
        view.centerOn(rect.center())
        start = view.mapFromScene(QPointF(rect.center().x(), rect.center().y()))
        vp = view.viewport()
        button, plain = Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier
        QTest.mousePress(vp, button, plain, start)
        moves = [0]

        def drag() -> None:
            moves[0] += 1
            QTest.mouseMove(vp, start + QPoint(3 * (moves[0] % 20), 0))

        return drag, lambda: QTest.mouseRelease(vp, button, plain, start)
    return _none, _none


def _none() -> None:
    return None


def _pump(app, seconds: float) -> None:
    """Run the event loop for about `seconds`."""
    end = time.perf_counter() + seconds
    while True:
        app.processEvents()
        left = end - time.perf_counter()
        if left <= 0:
            return
        time.sleep(min(left, 0.002))


def _wait(app, done: Callable[[], bool], timeout: float) -> None:
    end = time.perf_counter() + timeout
    while not done() and time.perf_counter() < end:
        _pump(app, 0.01)


if __name__ == "__main__":
    main()
    sys.stdout.flush()
    os._exit(0)  # the findings overlay's background check on 20k clips need not finish
