"""Audio-editor habits: S split, Alt+arrow nudge, Ctrl+D into free space, markers, loop region,
merge in place, overlaps shown, muted tracks dimmed."""

from __future__ import annotations

import math

import pytest
from PySide6.QtCore import QPoint, Qt
from PySide6.QtTest import QTest

from timeline import edits
from timeline.files import projectfile

from .helpers import click, clip_point, drag

ALT = Qt.KeyboardModifier.AltModifier
CTRL = Qt.KeyboardModifier.ControlModifier
LEFT = Qt.MouseButton.LeftButton
PX = 200.0


def ruler_x(win, u: float) -> int:
    return round(win.view.lane_geometry.x(u) - win.view.horizontalScrollBar().value())


def ruler_drag(win, u0: float, u1: float, y: int = 30) -> None:
    a, b = QPoint(ruler_x(win, u0), y), QPoint(ruler_x(win, u1), y)
    QTest.mousePress(win.ruler, LEFT, pos=a)
    for i in range(1, 5):
        QTest.mouseMove(win.ruler, a + (b - a) * (i / 4))
    QTest.mouseRelease(win.ruler, LEFT, pos=b)


def test_s_splits_at_the_playhead_set_on_the_ruler(window):
    win = window
    c1 = win.ids["c1"]  # 0.5 .. 1.5 s
    QTest.mouseClick(win.ruler, LEFT, pos=QPoint(ruler_x(win, 0.8), 30))
    QTest.keyClick(win, Qt.Key.Key_S)
    clips = win.doc.project.track(win.ids["t1"]).clips
    assert [(c.start, c.end) for c in clips] == [
        pytest.approx((0.5, 0.8), abs=1 / PX),
        pytest.approx((0.8, 1.5), abs=1 / PX),
    ]
    assert clips[0].id == c1
    QTest.keyClick(win, Qt.Key.Key_Z, CTRL)
    assert len(win.doc.project.track(win.ids["t1"]).clips) == 1


def test_alt_arrows_nudge_by_one_grid_step_and_plain_arrows_do_not(window):
    win = window
    c1 = win.ids["c1"]
    click(win, clip_point(win, c1))
    step = win.view.scene().grid_step()
    assert step == pytest.approx(0.125)  # 0.5 s ruler steps at 200 px/s, four grid lines each
    QTest.keyClick(win, Qt.Key.Key_Right, ALT)
    QTest.keyClick(win, Qt.Key.Key_Right, ALT)
    assert win.doc.project.find_clip(c1)[1].start == pytest.approx(0.75)
    QTest.keyClick(win, Qt.Key.Key_Left, ALT)
    assert win.doc.project.find_clip(c1)[1].start == pytest.approx(0.625)
    assert win.doc.history.undo_label == "nudge"
    QTest.keyClick(win.view.viewport(), Qt.Key.Key_Right)
    assert win.doc.project.find_clip(c1)[1].start == pytest.approx(0.625)
    for _ in range(10):  # never before 0
        QTest.keyClick(win, Qt.Key.Key_Left, ALT)
    assert win.doc.project.find_clip(c1)[1].start == 0.0


def test_ctrl_d_puts_the_copy_in_the_first_gap_that_fits(window):
    win = window
    c1 = win.ids["c1"]  # 0.5 .. 1.5 s on t1
    ramp = win.ids["ramp"]
    win.doc.apply("place", edits.add_clip, win.ids["t1"], ramp, 1.7)  # 1.7 .. 2.2 blocks
    click(win, clip_point(win, c1))
    QTest.keyClick(win, Qt.Key.Key_D, CTRL)
    track = win.doc.project.track(win.ids["t1"])
    copy = win.doc.project.find_clip(win.doc.selected_clips[0])[1]
    assert copy.tile_id == win.ids["sine"]
    assert copy.start == pytest.approx(2.2)  # not 1.5, where it would cover the ramp
    assert len(track.clips) == 3
    assert not any(win.view.clip_item(c.id).covered for c in track.clips)


def test_overlapping_clips_are_marked_and_muted_tracks_dimmed(window):
    win = window
    c1 = win.ids["c1"]
    c2 = win.ids["c2"]  # 2.0 .. 2.5 s on t2
    # drag the ramp up a lane and left, onto the end of the sine
    lane = round(win.view.lane_geometry.lane_height)
    drag(win, clip_point(win, c2, 0.1), clip_point(win, c2, 0.1) + QPoint(-round(0.8 * PX), -lane))
    track = win.doc.project.find_clip(c2)[0]
    assert track.id == win.ids["t1"]
    item = win.view.clip_item(c1)
    assert item.covered and item.covered[0][1] - item.covered[0][0] > 0.1
    assert "overlaps another clip" in item.toolTip()
    QTest.mouseClick(win.headers.headers[win.ids["t1"]].mute, LEFT)
    assert win.doc.project.track(win.ids["t1"]).mute
    assert win.view.clip_item(c1).opacity() == pytest.approx(0.35)
    assert "muted" in win.view.clip_item(c1).toolTip()
    QTest.mouseClick(win.headers.headers[win.ids["t1"]].mute, LEFT)
    assert win.view.clip_item(c1).opacity() == 1.0


def test_m_adds_a_marker_shown_on_the_ruler_and_saved(window, tmp_path):
    win = window
    QTest.mouseClick(win.ruler, LEFT, pos=QPoint(ruler_x(win, 1.0), 30))
    QTest.keyClick(win, Qt.Key.Key_M)
    QTest.mouseClick(win.ruler, LEFT, pos=QPoint(ruler_x(win, 2.0), 30))
    QTest.keyClick(win, Qt.Key.Key_M)
    assert [(m.name, m.at) for m in win.doc.project.markers] == [
        ("M1", pytest.approx(1.0, abs=1 / PX)),
        ("M2", pytest.approx(2.0, abs=1 / PX)),
    ]
    assert win.ruler.marker_at(ruler_x(win, 1.0), 6) == 0
    # rename by double-clicking the flag, move by dragging it
    win.ruler.ask_name = lambda current: "hit"
    QTest.mouseDClick(win.ruler, LEFT, pos=QPoint(ruler_x(win, 1.0) + 2, 6))
    assert win.doc.project.markers[0].name == "hit"
    ruler_drag(win, 2.0, 2.5, y=6)
    assert win.doc.project.markers[1].at == pytest.approx(2.5, abs=1 / PX)
    # jump between markers with [ and ]
    QTest.keyClick(win, Qt.Key.Key_BracketLeft)
    assert win.view.scene().playhead_u == pytest.approx(win.doc.project.markers[0].at)
    assert win.transport.where.text() == f"{win.doc.project.markers[0].at:.3f} s"
    QTest.keyClick(win, Qt.Key.Key_BracketRight)
    assert win.view.scene().cursor_u == pytest.approx(win.doc.project.markers[1].at)
    assert win.save_to(tmp_path / "m.htl")
    again = projectfile.load(tmp_path / "m.htl")
    assert [m.name for m in again.markers] == ["hit", "M2"]
    QTest.keyClick(win, Qt.Key.Key_Z, CTRL)  # the move
    assert win.doc.project.markers[1].at == pytest.approx(2.0, abs=1 / PX)


def test_fan_knob_settings_are_markers_on_the_degrees_ruler(qtbot):
    from pathlib import Path

    from timeline.gui.main_window import MainWindow

    win = MainWindow()
    qtbot.addWidget(win)
    win.show()
    assert win.open_path(Path(__file__).resolve().parents[2] / "projects" / "fan_knob.htl")
    names = [(m.name, round(math.degrees(m.at))) for m in win.doc.project.markers]
    assert names == [("Off", 50), ("Lo", 110), ("Med", 170), ("Hi", 230)]
    x = round(win.ruler.x_of(win.doc.project.markers[1].at))
    assert "marker Lo at 110°" in win.ruler._tip(win.ruler.marker_at(x, 5), x)
    win.player.close()


def test_loop_region_dragged_on_the_ruler_loops_playback(window, qtbot):
    win = window
    ruler_drag(win, 0.6, 1.0)
    loop = win.doc.project.loop
    assert (loop.start, loop.stop) == (
        pytest.approx(0.6, abs=1 / PX),
        pytest.approx(1.0, abs=1 / PX),
    )
    assert win.transport.loop.isChecked()
    seen: list[float] = []
    win.player.position.connect(seen.append)
    QTest.keyClick(win, Qt.Key.Key_Space)
    qtbot.waitUntil(
        lambda: any(b < a for a, b in zip(seen, seen[1:], strict=False)), timeout=15_000
    )
    QTest.keyClick(win, Qt.Key.Key_Space)
    assert min(seen) >= loop.start - 1e-9 and max(seen) < loop.stop
    # right-click menu clears it
    menu = win.ruler.menu_at(ruler_x(win, 0.8), 30)
    [clear] = [a for a in menu.actions() if a.text() == "Clear loop region"]
    clear.trigger()
    assert win.doc.project.loop is None


def test_ctrl_m_merges_in_place_as_one_step(window):
    win = window
    before = win.doc.project
    c1 = win.ids["c1"]
    click(win, clip_point(win, c1))
    QTest.keyClick(win, Qt.Key.Key_M, CTRL)
    track = win.doc.project.track(win.ids["t1"])
    assert len(track.clips) == 1 and track.clips[0].id != c1
    assert track.clips[0].start == pytest.approx(0.5)
    assert win.doc.history.undo_label == "merge in place"
    QTest.keyClick(win, Qt.Key.Key_Z, CTRL)
    assert win.doc.project == before
