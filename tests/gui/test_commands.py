"""Keyboard and menu commands, palette drops, tabs, variants, the title and closing."""

from __future__ import annotations

import pytest
from PySide6.QtCore import QPoint, QPointF, Qt
from PySide6.QtGui import QWheelEvent
from PySide6.QtTest import QTest
from PySide6.QtWidgets import QApplication

from timeline.gui.gestures.palette_drop import tile_mime
from timeline.tiles import SplineTile

from .helpers import click, clip_point, send_drop, view_point

CTRL = Qt.KeyboardModifier.ControlModifier
PX = 200.0


def key(win, k, mods=Qt.KeyboardModifier.NoModifier) -> None:
    QTest.keyClick(win, k, mods)


def test_palette_drop_makes_a_clip_on_that_track(window):
    win = window
    before = win.doc.project
    lane = win.view.lane_geometry.lane_top(2) + 30  # the stiffness track
    send_drop(win, tile_mime(win.ids["ramp"]), view_point(win, QPointF(3.0 * PX, lane)))
    track = win.doc.project.track(win.ids["t3"])
    assert len(track.clips) == 1
    assert track.clips[0].tile_id == win.ids["ramp"]
    assert track.clips[0].start == pytest.approx(3.0, abs=1 / PX)
    key(win, Qt.Key.Key_Z, CTRL)
    assert win.doc.project == before


def test_split_duplicate_delete_with_keys(window):
    win = window
    c1 = win.ids["c1"]
    click(win, clip_point(win, c1, 0.5))  # selects the clip and puts the cursor at its middle
    key(win, Qt.Key.Key_I, CTRL)
    clips = win.doc.project.track(win.ids["t1"]).clips
    assert [round(c.start, 3) for c in clips] == [0.5, round(clips[1].start, 3)]
    assert clips[1].start == pytest.approx(1.0, abs=1 / PX)
    assert clips[0].end == pytest.approx(clips[1].start)
    win.doc.select_clips([clips[1].id])
    key(win, Qt.Key.Key_D, CTRL)
    assert len(win.doc.project.track(win.ids["t1"]).clips) == 3
    key(win, Qt.Key.Key_Delete)
    assert len(win.doc.project.track(win.ids["t1"]).clips) == 2
    for expected in (3, 2, 1):
        key(win, Qt.Key.Key_Z, CTRL)
        assert len(win.doc.project.track(win.ids["t1"]).clips) == expected
    key(win, Qt.Key.Key_Z, Qt.KeyboardModifier.ControlModifier | Qt.KeyboardModifier.ShiftModifier)
    assert len(win.doc.project.track(win.ids["t1"]).clips) == 2


def test_invert_and_reverse_from_the_menu(window):
    win = window
    c1 = win.ids["c1"]
    click(win, clip_point(win, c1))
    menu_edit = next(a for a in win.menuBar().actions() if a.text() == "&Edit").menu()
    actions = {a.text(): a for a in menu_edit.actions()}
    actions["In&vert about mirror line"].trigger()
    actions["Re&verse"].trigger()
    clip = win.doc.project.find_clip(c1)[1]
    assert clip.scale == -1.0 and clip.reverse
    key(win, Qt.Key.Key_Z, CTRL)
    key(win, Qt.Key.Key_Z, CTRL)
    clip = win.doc.project.find_clip(c1)[1]
    assert clip.scale == 1.0 and not clip.reverse


def test_a_refused_edit_goes_to_the_message_bar_and_changes_nothing(window):
    win = window
    before = win.doc.project
    click(win, view_point(win, QPointF(5.0 * PX, 20)))  # cursor outside every clip
    key(win, Qt.Key.Key_I, CTRL)
    assert win.doc.project == before
    assert "cursor inside a clip" in win.messages.text
    assert win.messages.history[-1][1] == "error"


def test_variants_saved_and_switched_with_one_key(window):
    win = window
    c1 = win.ids["c1"]
    key(win, Qt.Key.Key_V, CTRL | Qt.KeyboardModifier.ShiftModifier)  # variant A
    click(win, clip_point(win, c1))
    win.reverse()
    key(win, Qt.Key.Key_V, CTRL | Qt.KeyboardModifier.ShiftModifier)  # variant B (reversed)
    assert [v.name for v in win.doc.project.variants] == ["A", "B"]
    key(win, Qt.Key.Key_V)
    assert win.doc.project.active_variant == "A"
    assert not win.doc.project.find_clip(c1)[1].reverse
    key(win, Qt.Key.Key_V)
    assert win.doc.project.active_variant == "B"
    assert win.doc.project.find_clip(c1)[1].reverse


def test_palette_tabs_add_rename_remove(window):
    win = window
    pal = win.tile_palette
    pal.name.setText("Buzzes")
    QTest.mouseClick(pal.add_button, Qt.MouseButton.LeftButton)
    assert win.doc.project.tab("Buzzes").role == "user"
    assert pal.current_tab() == "Buzzes"
    pal.name.setText("Clicks")
    QTest.mouseClick(pal.rename_button, Qt.MouseButton.LeftButton)
    assert [t.name for t in win.doc.project.palette][-1] == "Clicks"
    QTest.mouseClick(pal.remove_button, Qt.MouseButton.LeftButton)
    assert [t.name for t in win.doc.project.palette] == ["Templates", "Scratch"]
    pal.tabs.setCurrentIndex(0)
    QTest.mouseClick(pal.remove_button, Qt.MouseButton.LeftButton)  # disabled for Templates
    assert [t.name for t in win.doc.project.palette] == ["Templates", "Scratch"]


def test_track_header_gain_mute_solo_and_add_remove(window):
    win = window
    header = win.headers.headers[win.ids["t1"]]
    header.gain.setValue(0.5)
    QTest.mouseClick(header.mute, Qt.MouseButton.LeftButton)
    QTest.mouseClick(header.solo, Qt.MouseButton.LeftButton)
    track = win.doc.project.track(win.ids["t1"])
    assert (track.gain, track.mute, track.solo) == (0.5, True, True)
    new_id = win.headers.add_track("damping")
    assert win.doc.project.track(new_id).kind == "damping"
    assert new_id in win.headers.headers
    QTest.mouseClick(win.headers.headers[new_id].remove, Qt.MouseButton.LeftButton)
    assert new_id not in {t.id for t in win.doc.project.tracks}


def test_zoom_keys_and_ctrl_wheel(window):
    win = window
    before = win.view.lane_geometry.px_per_unit
    key(win.view, Qt.Key.Key_Equal, CTRL)
    assert win.view.lane_geometry.px_per_unit == pytest.approx(before * 1.25)
    width = win.view.clip_scene_rect(win.ids["c1"]).width()
    assert width == pytest.approx(1.25 * PX, abs=1)
    key(win.view, Qt.Key.Key_Minus, CTRL)
    assert win.view.lane_geometry.px_per_unit == pytest.approx(before)
    at = QPointF(300, 40)
    wheel = QWheelEvent(
        at,
        QPointF(win.view.viewport().mapToGlobal(at.toPoint())),
        QPoint(0, 0),
        QPoint(0, 120),
        Qt.MouseButton.NoButton,
        CTRL,
        Qt.ScrollPhase.NoScrollPhase,
        False,
    )
    QApplication.sendEvent(win.view.viewport(), wheel)
    assert win.view.lane_geometry.px_per_unit == pytest.approx(before * 1.25)


def test_title_shows_unsaved_changes_and_close_asks_once(window, tmp_path):
    win = window
    assert not win.windowTitle().startswith("*")
    win.reverse() if win.doc.select_clips([win.ids["c1"]]) is None else None
    assert win.windowTitle().startswith("*")
    assert win.save_to(tmp_path / "a.htl")
    assert win.windowTitle() == "a.htl — Haptic Timeline"
    win.doc.select_clips([win.ids["c1"]])
    win.invert()
    win.close()
    assert win.asked == 1


def test_spline_point_drag_number_box_and_range_to_palette(window):
    win = window
    project = win.doc.project
    from timeline import edits

    spline = SplineTile(((0.0, 0.0), (0.5, 1.0), (1.0, 0.0)), 1.0)
    project, tile_id = edits.add_tile(project, spline)
    win.doc.replace("add spline", project)
    win.doc.select_tile(tile_id)
    canvas = win.editor.canvas
    p = QPoint(int(canvas.x_of(0.5)), int(canvas.y_of(1.0)))
    QTest.mousePress(canvas, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, p)
    QTest.mouseMove(canvas, p + QPoint(0, 20))
    QTest.mouseMove(canvas, p + QPoint(0, 40))
    QTest.mouseRelease(
        canvas, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, p + QPoint(0, 40)
    )
    moved = win.doc.project.tile(tile_id).points[1]
    assert moved[0] == pytest.approx(0.5, abs=0.01) and moved[1] < 0.9
    steps = len(win.doc.history)
    win.editor.v_box.setValue(0.25)
    win.editor.v_box.editingFinished.emit()
    assert win.doc.project.tile(tile_id).points[1] == pytest.approx((0.5, 0.25), abs=0.01)
    assert len(win.doc.history) == steps + 1
    y = int(canvas.y_of(0.0)) + 5
    QTest.mousePress(
        canvas,
        Qt.MouseButton.LeftButton,
        Qt.KeyboardModifier.ShiftModifier,
        QPoint(int(canvas.x_of(0.25)), y),
    )
    QTest.mouseMove(canvas, QPoint(int(canvas.x_of(0.75)), y))
    QTest.mouseRelease(
        canvas,
        Qt.MouseButton.LeftButton,
        Qt.KeyboardModifier.ShiftModifier,
        QPoint(int(canvas.x_of(0.75)), y),
    )
    QTest.mouseClick(win.editor.to_palette, Qt.MouseButton.LeftButton)
    new = win.doc.project.tile(win.doc.project.tab("Scratch").tile_ids[-1])
    assert new.duration == pytest.approx(0.5, abs=0.02)
    assert new.points[1] == pytest.approx((0.25, 0.25), abs=0.02)
