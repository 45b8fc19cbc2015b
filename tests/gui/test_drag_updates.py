"""What a clip drag keeps true while it does less per mouse move: the panels show the dragged
clip's final values, snapping lands where a search over every clip edge lands, the snap line is
where the drag snapped, and the lanes' scroll bars are not repainted."""

from __future__ import annotations

import pytest
from PySide6.QtCore import QEvent, QObject, QPoint, Qt
from PySide6.QtTest import QTest
from PySide6.QtWidgets import QApplication

from timeline import edits
from timeline.gui.inspector_fields import shown_axis
from timeline.gui.timeline_view import SNAP_PX
from timeline.tiles import generator

from .helpers import clip_point

LEFT, NO = Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier


def _crowded_project():
    """A 0.3 s clip on the first track and 3 tracks of 0.2 s clips at uneven starts: a clip edge
    every few hundredths of a second, so each move has several edges within snapping reach."""
    project = edits.new_project(templates=False)
    project, tile = edits.add_tile(project, generator("sine", 0.2, frequency=20))
    project, long_tile = edits.add_tile(project, generator("sine", 0.3, frequency=20))
    project, first = edits.add_track(project, "drive")
    project, dragged = edits.add_clip(project, first, long_tile, 1.0)
    for i in range(3):
        project, track = edits.add_track(project, "drive")
        for j in range(12):
            project, _ = edits.add_clip(project, track, tile, 0.61 * j + 0.137 * i + 0.0091 * j * j)
    return project, dragged


def _brute_snap(project, value: float, dragged: str, grid: float, tolerance: float) -> float:
    """The nearest edge of any other clip (or the origin) within tolerance, else the nearest grid
    line within it, else the value: found by looking at every clip."""
    edges = [0.0] + [
        e for t in project.tracks for c in t.clips if c.id != dragged for e in (c.start, c.end)
    ]
    best = min(edges, key=lambda e: abs(e - value))
    if abs(best - value) <= tolerance:
        return best
    line = round(value / grid) * grid
    return line if abs(line - value) <= tolerance else value


def test_a_snapped_drag_lands_where_a_search_of_every_edge_lands(window):
    win, view = window, window.view
    project, clip_id = _crowded_project()
    win.doc.replace("crowded", project)
    view.snapping = True
    start, duration = (lambda c: (c.start, c.duration))(project.find_clip(clip_id)[1])
    g = view.lane_geometry
    grid, tolerance = view.scene().grid_step(), g.u(SNAP_PX)
    press = clip_point(win, clip_id)
    vp = view.viewport()
    QTest.mousePress(vp, LEFT, NO, press)
    snapped_moves = 0
    for step in range(1, 15):
        at = press + QPoint(7 * step, 0)
        QTest.mouseMove(vp, at)
        raw = start + g.u(7 * step)
        want = _brute_snap(project, raw, clip_id, grid, tolerance)
        line = want if want != raw else None
        if want == raw:
            end = _brute_snap(project, raw + duration, clip_id, grid, tolerance)
            want, line = end - duration, (end if end != raw + duration else None)
        assert win.doc.project.find_clip(clip_id)[1].start == pytest.approx(want, abs=1e-12)
        assert view.snap_line.at == (None if line is None else pytest.approx(line, abs=1e-12))
        assert view.snap_line.line.isVisible() == (line is not None)
        if line is not None:
            assert view.snap_line.line.line().x1() == pytest.approx(g.x(line))
            snapped_moves += 1
    QTest.mouseRelease(vp, LEFT, NO, at)
    assert snapped_moves >= 10  # the case has candidates: most moves snap
    assert win.doc.project.find_clip(clip_id)[1].start == pytest.approx(want, abs=1e-12)
    assert not view.snap_line.line.isVisible()


def test_after_a_drag_the_inspector_shows_the_clips_new_start_and_one_undo_takes_it_back(window):
    win = window
    c1 = win.ids["c1"]  # at 0.5 s on t1, 200 px per second
    press = clip_point(win, c1)
    vp = win.view.viewport()
    QTest.mousePress(vp, LEFT, NO, press)
    for step in range(1, 9):
        QTest.mouseMove(vp, press + QPoint(9 * step, 0))
    QTest.mouseRelease(vp, LEFT, NO, press + QPoint(72, 0))
    QApplication.processEvents()  # one turn of the event loop
    start = win.doc.project.find_clip(c1)[1].start
    assert start == pytest.approx(0.5 + 72 / 200.0)
    page = win.inspector.pages["clip"]
    assert page.start.value() == pytest.approx(shown_axis(start, "time"), abs=1e-4)
    assert page.length.value() == pytest.approx(1.0, abs=1e-4)
    assert win.view.readout.isHidden()
    win.doc.undo()  # the whole drag is one step
    QApplication.processEvents()
    assert win.doc.project.find_clip(c1)[1].start == 0.5
    assert page.start.value() == pytest.approx(0.5, abs=1e-4)


class _ScrollBarPaints(QObject):
    def __init__(self) -> None:
        super().__init__()
        self.count = 0

    def eventFilter(self, watched: QObject, event: QEvent) -> bool:  # noqa: N802 - Qt's name
        self.count += event.type() == QEvent.Type.Paint
        return False


def test_a_drag_whose_readout_changes_width_repaints_no_scroll_bar(window):
    win, view = window, window.view
    project = win.doc.project
    for _ in range(12):  # lanes below the window's height: both scroll bars shown
        project, _track = edits.add_track(project, "drive")
    win.doc.replace("more tracks", project)
    QApplication.processEvents()
    counter = _ScrollBarPaints()
    bars = (view.horizontalScrollBar(), view.verticalScrollBar())
    assert all(bar.isVisible() for bar in bars)
    c1 = win.ids["c1"]
    press = clip_point(win, c1)
    vp = view.viewport()
    widths = set()
    QTest.mousePress(vp, LEFT, NO, press)
    QApplication.processEvents()  # the press selects the clip; what follows is the drag
    for bar in bars:
        bar.installEventFilter(counter)
    for step in range(3, 14):  # starts 0.515 to 0.565 s: readouts of unequal widths
        QTest.mouseMove(vp, press + QPoint(step, 0))
        QApplication.processEvents()
        widths.add(view.readout.width())
    QTest.mouseRelease(vp, LEFT, NO, press + QPoint(13, 0))
    QApplication.processEvents()
    for bar in bars:
        bar.removeEventFilter(counter)
    assert len(widths) > 1  # the readout did change width
    assert counter.count == 0
    assert win.doc.project.find_clip(c1)[1].start == pytest.approx(0.5 + 13 / 200.0)
