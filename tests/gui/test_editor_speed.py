"""What keeps the editor fast at 20,000 clips, asserted as behaviour (timed by
`haptic-timeline bench editor`, never here): stale limits checks are stopped, closing with checks
queued says nothing, zoom moves no clip yet places each at start x scale, the waveform editor's
decimated curve keeps every column's extremes, the first paint loads no scipy.signal (nor
importlib.metadata, html, the export dialog, the sound analysis panel or the panels and the
findings overlay built after it), and those panels take the places the first frame kept for
them."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import threading
from pathlib import Path

import numpy as np
import pytest
from PySide6.QtCore import QPoint, QPointF, Qt
from PySide6.QtTest import QTest

from timeline import edits
from timeline.gui import findings_overlay
from timeline.gui.waveform_editor import decimate
from timeline.tiles import generator

from .helpers import clip_point

EXAMPLE = Path(__file__).resolve().parents[2] / "projects" / "fan_knob.htl"


@pytest.fixture
def slow_checks(monkeypatch):
    """Checks that run until told to stop (or released), stepping through `interrupt`."""
    release = threading.Event()
    started: list[int] = []

    def check(project, info, hand=None, interrupt=lambda: None):  # noqa: ANN001, ARG001
        started.append(1)
        while not release.wait(0.01):
            interrupt()
        from timeline.limits.check import Report

        return Report((), ())

    import timeline.limits.check

    monkeypatch.setattr(timeline.limits.check, "check", check)
    yield release, started
    release.set()


def _wait_until(qtbot, condition) -> None:  # noqa: ANN001
    qtbot.waitUntil(condition, timeout=10_000)


def _fresh_counts(win):  # noqa: ANN001, ANN202
    """The window's findings with the counts of its first (real) check cleared and a slow check
    started."""
    findings = win.findings
    assert findings.settled and not findings.busy
    findings.counts.clear()
    findings.schedule()
    return findings


def test_a_slow_drag_starts_no_check_and_leaves_none_stale(window, qtbot, monkeypatch, slow_checks):
    """Pauses in a drag longer than the check's delay start no check (each used to start one,
    made stale by the next move); the check running when the drag began is stopped, its result
    dropped, and the state the drag leaves is checked once the mouse lets go."""
    monkeypatch.setattr(findings_overlay, "DELAY_MS", 20)
    release, started = slow_checks
    win = window
    findings = _fresh_counts(win)
    _wait_until(qtbot, lambda: findings.counts["started"] == 1)  # running as the drag begins
    vp = win.view.viewport()
    at = clip_point(win, win.ids["c1"])
    QTest.mousePress(vp, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, at)
    for step in range(1, 6):
        QTest.mouseMove(vp, at + QPoint(4 * step, 0))
        qtbot.wait(60)  # a pause three times the delay
        assert findings.counts["started"] == 1 and not findings.settled
    _wait_until(qtbot, lambda: not findings.stale_running())  # stopped at its next step
    assert findings.counts["cancelled"] == 1 and findings.report is not None
    shown = findings.report
    QTest.mouseRelease(vp, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, at)
    _wait_until(qtbot, lambda: findings.counts["started"] == 2)  # the released state's check
    assert findings.busy and not findings.stale_running() and findings.report is shown
    release.set()
    _wait_until(qtbot, lambda: findings.settled)
    counts = findings.counts
    assert (counts["started"], counts["finished"], counts["cancelled"]) == (2, 1, 1)
    assert len(started) == 2 and findings.report is not shown


def test_queued_checks_are_dropped_not_run(window, qtbot, monkeypatch, slow_checks):
    release, started = slow_checks
    findings = _fresh_counts(window)
    _wait_until(qtbot, lambda: findings.busy and findings.counts["started"] == 1)
    findings._start()  # a second check queued behind the first: the first is told to stop
    findings._start()  # a third: the second, still queued, is dropped without running
    _wait_until(qtbot, lambda: not findings.stale_running() and findings.counts["started"] == 2)
    assert findings.counts["cancelled"] == 2  # the first stopped, the second dropped
    release.set()
    _wait_until(qtbot, lambda: not findings.busy)
    assert len(started) == 2 and findings.counts["finished"] == 1


def test_closing_with_checks_queued_says_nothing(window, qtbot, slow_checks, capfd):
    findings = _fresh_counts(window)
    capfd.readouterr()  # what opening the window printed (the offscreen platform's notes)
    _wait_until(qtbot, lambda: findings.counts["started"] == 1)
    findings._start()  # the running check is told to stop, a second queued
    findings._start()  # the second dropped, a third queued
    window.close()  # the third dropped
    _wait_until(qtbot, lambda: not findings.stale_running() and not findings._running)
    qtbot.wait(50)
    out, err = capfd.readouterr()
    assert "Traceback" not in err and "Error" not in err and out == ""
    assert findings.counts["cancelled"] == 3 and findings.counts["finished"] == 0


def test_zoom_moves_no_clip_and_places_each_at_start_times_scale(window, monkeypatch):
    from timeline.gui.clip_item import ClipItem

    project = edits.new_project(templates=False)
    project, tile = edits.add_tile(project, generator("sine", 0.2, frequency=20))
    for lane in range(3):
        project, track = edits.add_track(project, "drive")
        for j in range(40):
            project, _ = edits.add_clip(project, track, tile, 0.37 * j + 0.05 * lane)
    window.doc.replace("many clips", project)
    updated: list[str] = []
    original = ClipItem.update_from

    def counting(item, clip, *args):  # noqa: ANN001
        updated.append(clip.id)
        return original(item, clip, *args)

    monkeypatch.setattr(ClipItem, "update_from", counting)
    for factor in (1.25, 1.25, 0.5, 3.0):
        window.view.zoom(factor)
    assert updated == []
    scale = window.view.lane_geometry.px_per_unit
    for lane, track in enumerate(window.doc.project.tracks):
        for clip in track.clips:
            rect = window.view.clip_item(clip.id).sceneBoundingRect()
            assert rect.left() + 1 == pytest.approx(clip.start * scale)  # its pixel of outline
            assert rect.width() - 2 == pytest.approx(clip.duration * scale)
            at = QPointF(clip.start * scale + 1.0, rect.center().y())
            assert window.view.scene().clip_at(at).clip.id == clip.id  # and is hit there
            assert window.view.lane_geometry.lane_at(at.y()) == lane


def test_the_decimated_curve_keeps_each_columns_min_and_max():
    rng = np.random.default_rng(4)
    data = np.cumsum(rng.standard_normal(100_003))
    at, values = decimate(data, 640)
    assert values.size == 2 * 640
    starts = (np.arange(640) * data.size) // 640  # columns as even as integers allow
    stops = np.r_[starts[1:], data.size]
    assert values[0::2].tolist() == [data[a:b].max() for a, b in zip(starts, stops, strict=True)]
    assert values[1::2].tolist() == [data[a:b].min() for a, b in zip(starts, stops, strict=True)]
    assert np.all(np.diff(at) >= 0) and at[0] >= 0 and at[-1] < data.size
    short = np.array([0.0, 1.0, -1.0])
    assert decimate(short, 640)[1].tolist() == short.tolist()  # fewer samples: all of them


def test_dragging_a_clip_does_not_repaint_the_waveform_editor(window, qtbot):
    win = window
    canvas = win.editor.canvas
    painted: list[int] = []
    original = canvas.paintEvent
    canvas.paintEvent = lambda event: (painted.append(1), original(event))
    vp = win.view.viewport()
    at = clip_point(win, win.ids["c1"])
    QTest.mousePress(vp, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, at)
    QTest.mouseMove(vp, at + QPoint(5, 0))
    qtbot.wait(20)  # the pressed clip's tile is shown
    assert win.editor.tile_id == win.ids["sine"]
    painted.clear()
    for step in range(2, 7):
        QTest.mouseMove(vp, at + QPoint(5 * step, 0))
        qtbot.wait(5)
    end = at + QPoint(30, 0)
    QTest.mouseRelease(vp, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, end)
    qtbot.wait(20)
    assert win.doc.project.find_clip(win.ids["c1"])[1].start == pytest.approx(0.5 + 30 / 200)
    assert painted == []


PROBE = """
import json, os, sys
DEFERRED = (  # heavy libraries, and what only a command needs
    "scipy.signal", "numba", "importlib.metadata", "html", "timeline.gui.export_options",
    # the panels built after the first paint, and what only they need
    "timeline.gui.palette", "timeline.gui.inspector", "timeline.gui.waveform_editor",
    "timeline.gui.help", "timeline.gui.thumbnails",
    "timeline.gui.findings_overlay", "timeline.gui.rendered_overlay", "timeline.gui.trace_peaks",
    # what a menu, an import or an export needs
    "timeline.gui.step_menus", "timeline.gui.recent", "timeline.files.importing",
    "timeline.files.exporting", "timeline.gui.inspector_marker",
    # the play process's module, loaded when the warm-up after the first paint starts it
    "timeline.gui.play_process", "multiprocessing",
)
from PySide6.QtCore import QEvent, QObject, QTimer
from timeline.gui.app import launch
app, window = launch(sys.argv[1])
seen = {}
def painted():
    try:
        seen.update(modules=[m for m in DEFERRED if m in sys.modules])
        seen.update(analysis_panel=window.sound_import._panel is not None)
    finally:
        window.close()
        app.quit()
class First(QObject):
    def eventFilter(self, watched, event):
        if event.type() == QEvent.Type.Paint:
            watched.removeEventFilter(self)
            QTimer.singleShot(0, painted)
        return False
first = First()
window.view.viewport().installEventFilter(first)
app.exec()
print(json.dumps(seen))
"""


def test_the_first_paint_loads_neither_scipy_signal_nor_numba_nor_what_commands_need(tmp_path):
    env = {**os.environ, "QT_QPA_PLATFORM": "offscreen", "XDG_DATA_HOME": str(tmp_path)}
    done = subprocess.run(
        [sys.executable, "-c", PROBE, str(EXAMPLE)],
        capture_output=True,
        text=True,
        env=env,
        check=True,
    )
    found = json.loads(done.stdout.strip().splitlines()[-1])
    assert found == {"modules": [], "analysis_panel": False}


def _places(win) -> list[tuple[int, int, int, int]]:  # noqa: ANN001
    """Where the window's regions are: each splitter pane and the lanes, in window pixels."""
    widgets = [s.widget(i) for s in win.splitters().values() for i in range(s.count())]
    rects = [w.geometry().translated(w.parentWidget().mapTo(win, QPoint())) for w in widgets]
    rects.append(win.view.geometry().translated(win.view.parentWidget().mapTo(win, QPoint())))
    return [r.getRect() for r in rects]


def test_the_panels_built_after_the_first_paint_take_the_places_it_kept(qtbot):
    from timeline.files import projectfile
    from timeline.gui.findings_overlay import FindingsOverlay
    from timeline.gui.first_paint import after_first_paint
    from timeline.gui.inspector import Inspector
    from timeline.gui.main_window import MainWindow
    from timeline.gui.palette import Palette
    from timeline.gui.waveform_editor import WaveformEditor

    win = MainWindow(projectfile.load(EXAMPLE), EXAMPLE, panels_after_paint=True)
    qtbot.addWidget(win)
    first: dict[str, object] = {}

    def at_first_paint() -> None:  # runs before the window's own work after that paint
        first.update(places=_places(win), panels=win.findChildren(Palette))
        first.update(menu_empty=win.menus["edit"].isEmpty())
        first.update(overlays=win.findChildren(FindingsOverlay))

    after_first_paint(win.view.viewport(), at_first_paint)
    win.resize(800, 600)  # small: the panels' minimum sizes bind
    win.show()
    qtbot.waitUntil(lambda: bool(win.findChildren(Inspector)), timeout=10_000)
    assert first["panels"] == [] and first["menu_empty"] and first["places"]
    assert first["overlays"] == []  # the findings overlay too is built after the first paint
    assert _places(win) == first["places"]  # nothing moved or changed size
    assert len(win.findChildren(Palette)) == len(win.findChildren(WaveformEditor)) == 1
    undo = [a for a in win.menus["edit"].actions() if a.shortcut().toString() == "Ctrl+Z"]
    assert len(undo) == 1 and win.tile_palette.isVisible() and win.inspector.isVisible()
    qtbot.waitUntil(lambda: win.findings.settled, timeout=20_000)  # and it checks, unasked
    assert win.findChildren(FindingsOverlay) == [win.findings] and win.findings.counts["started"]


def test_headers_below_the_screen_are_built_later_in_the_tracks_order(qtbot):
    from timeline.gui.document import Document
    from timeline.gui.track_header import HeaderColumn

    project = edits.new_project(templates=False)
    for _ in range(5):
        project, _ = edits.add_track(project, "drive")
    doc = Document(project, None)
    column = HeaderColumn(doc, first_rows=2)
    qtbot.addWidget(column)
    ids = [t.id for t in project.tracks]
    assert list(column.headers) == ids[:2]
    doc.apply("rename", edits.set_track, ids[4], name="last")  # an edit first builds the rest
    assert list(column.headers) == ids and column.headers[ids[4]].name.text() == "last"
    rows = [column.rows.itemAt(i).widget() for i in range(len(ids))]
    assert rows == [column.headers[i] for i in ids]  # top to bottom in the tracks' order
    column.build_rest()  # nothing left to build
    assert len(column.findChildren(type(rows[0]))) == len(ids)
