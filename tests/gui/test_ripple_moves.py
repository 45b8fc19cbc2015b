"""Ripple edit for moves: dragging a clip later or earlier moves the later clips of its track by
as much, in one undo step; the earlier clips and other tracks stay."""

from __future__ import annotations

import pytest
from PySide6.QtCore import QPoint, Qt
from PySide6.QtTest import QTest

from timeline import edits

from .helpers import clip_point, drag

PX = 200.0  # the window fixture's pixels per second
CTRL = Qt.KeyboardModifier.ControlModifier


def add_clip(win, track: str, tile: str, start: float) -> str:
    project, clip_id = edits.add_clip(win.doc.project, win.ids[track], win.ids[tile], start)
    win.doc.replace("add clip", project)
    return clip_id


def starts(win, *clip_ids: str) -> list[float]:
    return [win.doc.project.find_clip(c)[1].start for c in clip_ids]


def test_ripple_moves_the_later_clips_of_the_track_along_in_one_step(window):
    win = window
    c1 = win.ids["c1"]  # 0.5 .. 1.5 s on t1
    before = add_clip(win, "t1", "ramp", 0.0)  # 0 .. 0.5 s: earlier, stays
    later = add_clip(win, "t1", "ramp", 2.0)
    last = add_clip(win, "t1", "ramp", 3.0)
    other = win.ids["c2"]  # 2.0 s on t2: another track, stays
    clips = (before, c1, later, last, other)
    win.ripple_action.trigger()
    assert win.view.ripple
    steps = len(win.doc.history)
    press = clip_point(win, c1)
    drag(win, press, press + QPoint(100, 0))  # 0.5 s later
    assert starts(win, *clips) == pytest.approx([0.0, 1.0, 2.5, 3.5, 2.0], abs=1e-9)
    assert len(win.doc.history) == steps + 1  # the whole drag is one step
    press = clip_point(win, c1)
    drag(win, press, press + QPoint(-60, 0))  # 0.3 s earlier: the later clips come back too
    assert starts(win, *clips) == pytest.approx([0.0, 0.7, 2.2, 3.2, 2.0], abs=1e-9)
    QTest.keyClick(win, Qt.Key.Key_Z, CTRL)
    assert starts(win, *clips) == pytest.approx([0.0, 1.0, 2.5, 3.5, 2.0], abs=1e-9)
    QTest.keyClick(win, Qt.Key.Key_Z, CTRL)
    assert starts(win, *clips) == [0.0, 0.5, 2.0, 3.0, 2.0]
    # moved to another track 0.2 s later, the later clips of its old track follow in time
    press = clip_point(win, c1)
    lane = win.view.lane_geometry.lane_top(win.view.lane_of(win.ids["t2"]))
    drag(win, press, QPoint(press.x() + 40, win.view.mapFromScene(0, lane + 20).y()))
    assert win.doc.project.find_clip(c1)[0].id == win.ids["t2"]
    assert starts(win, *clips) == pytest.approx([0.0, 0.7, 2.2, 3.2, 2.0], abs=1e-9)
    QTest.keyClick(win, Qt.Key.Key_Z, CTRL)
    # ripple off: only the dragged clip moves
    win.ripple_action.trigger()
    press = clip_point(win, c1)
    drag(win, press, press + QPoint(100, 0))
    assert starts(win, *clips) == pytest.approx([0.0, 1.0, 2.0, 3.0, 2.0], abs=1e-9)
