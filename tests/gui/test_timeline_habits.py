"""Audio-editor habits on the timeline, driven by mouse and keys: Shift+click extends the
selection, Ctrl+click toggles, headers drag to reorder, the playhead scrubs, a snap line shows,
the clip's top edge drags its gain, ripple edit, and touching clips' fade handles."""

from __future__ import annotations

import pytest
from PySide6.QtCore import QPoint, QPointF, Qt
from PySide6.QtTest import QTest

from timeline import edits
from timeline.gui.geometry import CLIP_MARGIN, LANE_HEIGHT

from .helpers import click, clip_point, drag, view_point

PX = 200.0
LEFT = Qt.MouseButton.LeftButton
SHIFT = Qt.KeyboardModifier.ShiftModifier
CTRL = Qt.KeyboardModifier.ControlModifier


def add_clip(win, track: str, tile: str, start: float) -> str:
    project, clip_id = edits.add_clip(win.doc.project, win.ids[track], win.ids[tile], start)
    win.doc.replace("add clip", project)
    return clip_id


def top_point(win, track: str, u: float, dy: float = 3.0) -> QPoint:
    """A viewport point near the top edge of a track's clips, at axis position u."""
    lane = win.view.lane_of(win.ids[track])
    y = win.view.lane_geometry.lane_top(lane) + CLIP_MARGIN + dy
    return view_point(win, QPointF(u * PX, y))


def test_shift_click_extends_the_selection_and_ctrl_click_toggles(window):
    win = window
    c1, c2 = win.ids["c1"], win.ids["c2"]
    between = add_clip(win, "t2", "ramp", 1.0)  # lane 2, between c1 (lane 1) and c2 in time
    elsewhere = add_clip(win, "t1", "ramp", 5.0)  # after both: not in the extended span
    click(win, clip_point(win, c1))
    click(win, clip_point(win, c2), SHIFT)
    assert win.doc.selected_clips == [c1, between, c2]  # the anchor first, then by track
    click(win, clip_point(win, between), CTRL)
    assert win.doc.selected_clips == [c1, c2]
    click(win, clip_point(win, elsewhere), CTRL)
    assert win.doc.selected_clips == [c1, c2, elsewhere]
    # pressing a selected clip keeps the selection and brings that clip up in the inspector
    click(win, clip_point(win, c2))
    assert sorted(win.doc.selected_clips) == sorted([c1, c2, elsewhere])
    assert win.inspector.pages["clip"].start.value() == 2.0
    assert win.doc.project == win.doc.history.project  # selecting edits nothing


def test_dragging_a_track_header_reorders_the_tracks(window):
    win = window
    t1, t2, t3 = (win.ids[k] for k in ("t1", "t2", "t3"))
    header = win.headers.headers[t1]
    start = QPoint(header.kind.x() + 5, header.kind.y() + 5)
    end = QPoint(start.x(), int(2.6 * LANE_HEIGHT))  # below the third header
    QTest.mousePress(header, LEFT, pos=start)
    for i in range(1, 5):
        QTest.mouseMove(header, start + (end - start) * (i / 4))
    assert win.headers.drop_line.isVisible()
    QTest.mouseRelease(header, LEFT, pos=end)
    assert [t.id for t in win.doc.project.tracks] == [t2, t3, t1]
    assert win.doc.history.undo_label == "move track Drive 1 to place 3"
    assert win.doc.selected_track == t1  # the pressed header's track is in the inspector
    QTest.keyClick(win, Qt.Key.Key_Z, CTRL)
    assert [t.id for t in win.doc.project.tracks] == [t1, t2, t3]


def test_dragging_the_playhead_on_the_ruler_scrubs_without_a_loop(window):
    win = window
    ruler = win.ruler
    steps = len(win.doc.history)
    start = QPoint(round(ruler.x_of(0.0)) + 2, 30)  # on the playhead
    end = QPoint(round(ruler.x_of(1.25)), 30)
    QTest.mousePress(ruler, LEFT, pos=start)
    for i in range(1, 5):
        QTest.mouseMove(ruler, start + (end - start) * (i / 4))
        assert win.view.scene().playhead_u == pytest.approx(
            ruler.u_of((start + (end - start) * (i / 4)).x())
        )
    QTest.mouseRelease(ruler, LEFT, pos=end)
    assert win.view.scene().playhead_u == pytest.approx(1.25, abs=1 / PX)
    assert win.view.scene().cursor_u == pytest.approx(1.25, abs=1 / PX)
    assert win.transport.where.text() == f"{win.view.scene().playhead_u:.3f} s"
    assert win.doc.project.loop is None and len(win.doc.history) == steps
    # the same drag started away from the playhead sets a loop region
    a, b = QPoint(round(ruler.x_of(2.0)), 30), QPoint(round(ruler.x_of(2.5)), 30)
    QTest.mousePress(ruler, LEFT, pos=a)
    QTest.mouseMove(ruler, b)
    QTest.mouseRelease(ruler, LEFT, pos=b)
    assert win.doc.project.loop is not None


def test_a_snap_line_shows_while_a_drag_is_snapped(window):
    win = window
    win.view.snapping = True
    c2 = win.ids["c2"]  # c1 ends at 1.5 s; c2 starts at 2.0 s
    vp = win.view.viewport()
    press = clip_point(win, c2)
    QTest.mousePress(vp, LEFT, Qt.KeyboardModifier.NoModifier, press)
    QTest.mouseMove(vp, press + QPoint(-40, 0))  # 0.2 s: not near an edge
    assert not win.view.snap_line.line.isVisible()
    near = press + QPoint(round(-0.48 * PX), 0)  # start 4 px from c1's end
    QTest.mouseMove(vp, near)
    line = win.view.snap_line
    assert line.line.isVisible() and line.at == 1.5
    assert line.line.line().x1() == pytest.approx(1.5 * PX)
    QTest.mouseRelease(vp, LEFT, Qt.KeyboardModifier.NoModifier, near)
    assert win.doc.project.find_clip(c2)[1].start == 1.5
    assert not line.line.isVisible()


def test_dragging_a_clips_top_edge_sets_its_gain(window):
    win = window
    c1 = win.ids["c1"]
    press = top_point(win, "t1", 1.0)  # the middle of the clip's top edge
    item = win.view.clip_item(c1)
    assert item.zone(item.mapFromScene(win.view.mapToScene(press))) == "gain"
    half = max(8.0, LANE_HEIGHT / 2 - 8)
    drag(win, press, press + QPoint(0, round(half)))  # half a lane down halves it
    clip = win.doc.project.find_clip(c1)[1]
    assert clip.gain == pytest.approx(0.5) and clip.scale == 1.0
    assert win.doc.history.undo_label == "clip gain"
    # Shift-drag on the body still scales about the mirror line, the gain staying
    body = clip_point(win, c1)
    drag(win, body, body + QPoint(0, -round(half)), SHIFT)
    clip = win.doc.project.find_clip(c1)[1]
    assert clip.scale == pytest.approx(2.0) and clip.gain == pytest.approx(0.5)


def test_ripple_edit_moves_the_later_clips_on_trim_and_delete(window):
    win = window
    c1 = win.ids["c1"]  # 0.5 .. 1.5 s on t1
    later = add_clip(win, "t1", "ramp", 2.0)
    other = win.ids["c2"]  # on another track: stays
    assert not win.view.ripple
    win.ripple_action.trigger()
    assert win.view.ripple and win.ripple_action.isChecked()
    edge = clip_point(win, c1, fx=0.995)
    drag(win, edge, edge + QPoint(-50, 0))  # trim the end 0.25 s earlier
    project = win.doc.project
    assert project.find_clip(c1)[1].end == pytest.approx(1.25, abs=1e-9)
    assert project.find_clip(later)[1].start == pytest.approx(1.75, abs=1e-9)
    assert project.find_clip(other)[1].start == 2.0
    click(win, clip_point(win, c1))
    QTest.keyClick(win.view.viewport(), Qt.Key.Key_Delete)
    project = win.doc.project
    assert project.find_clip(later)[1].start == pytest.approx(1.0, abs=1e-9)
    assert project.find_clip(other)[1].start == 2.0
    win.ripple_action.trigger()  # off: a delete leaves the gap
    click(win, clip_point(win, later))
    before = win.doc.project.find_clip(other)[1].start
    QTest.keyClick(win.view.viewport(), Qt.Key.Key_Delete)
    assert win.doc.project.find_clip(other)[1].start == before


def test_where_clips_touch_the_fade_handle_is_the_pointed_clips(window):
    win = window
    c1 = win.ids["c1"]  # 0.5 .. 1.5 s on t1
    right = add_clip(win, "t1", "ramp", 1.5)  # touches c1's end
    over_left = top_point(win, "t1", 1.5 - 3 / PX)
    drag(win, over_left, over_left + QPoint(-20, 0))
    project = win.doc.project
    assert project.find_clip(c1)[1].fade_out.length == pytest.approx(23 / PX, abs=1.5 / PX)
    assert project.find_clip(right)[1].fade_in.length == 0.0
    over_right = top_point(win, "t1", 1.5 + 3 / PX)
    drag(win, over_right, over_right + QPoint(20, 0))
    project = win.doc.project
    assert project.find_clip(right)[1].fade_in.length == pytest.approx(23 / PX, abs=1.5 / PX)
    assert project.find_clip(c1)[1].fade_out.length == pytest.approx(23 / PX, abs=1.5 / PX)
