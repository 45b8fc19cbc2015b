"""Each direct manipulation with the mouse changes the model as expected and undoes in one step."""

from __future__ import annotations

import pytest
from PySide6.QtCore import QPoint, QPointF, Qt
from PySide6.QtTest import QTest

from .helpers import clip_point, drag, view_point

SHIFT = Qt.KeyboardModifier.ShiftModifier
ALT = Qt.KeyboardModifier.AltModifier
PX = 200.0  # pixels per second in the window fixture


def undo(win, qtbot) -> None:
    QTest.keyClick(win, Qt.Key.Key_Z, Qt.KeyboardModifier.ControlModifier)


def clip(win, clip_id):
    return win.doc.project.find_clip(clip_id)


def test_move_along_the_track(window, qtbot):
    c1 = window.ids["c1"]
    before = window.doc.project
    start = clip_point(window, c1)
    drag(window, start, start + QPoint(100, 0))
    track, moved = clip(window, c1)
    assert moved.start == pytest.approx(0.5 + 100 / PX, abs=1 / PX)
    assert track.id == window.ids["t1"]
    assert len(window.doc.history) == 2  # one undo step for the whole drag
    undo(window, qtbot)
    assert window.doc.project == before


def test_move_across_tracks_takes_the_new_tracks_meaning(window, qtbot):
    c1 = window.ids["c1"]
    before = window.doc.project
    start = clip_point(window, c1)
    drag(window, start, start + QPoint(0, 2 * window.view.lane_geometry.lane_height))
    track, moved = clip(window, c1)
    assert track.id == window.ids["t3"] and track.kind == "stiffness"
    assert moved.start == pytest.approx(0.5)
    undo(window, qtbot)
    assert window.doc.project == before


def test_trim_right_edge(window, qtbot):
    c1 = window.ids["c1"]
    before = window.doc.project
    rect = window.view.clip_scene_rect(c1)
    start = view_point(window, QPointF(rect.right() - 2, rect.center().y()))
    drag(window, start, start - QPoint(60, 0))
    _, trimmed = clip(window, c1)
    assert trimmed.start == pytest.approx(0.5)
    assert trimmed.end == pytest.approx(1.5 - 60 / PX, abs=1.5 / PX)
    assert trimmed.stretch == 1.0
    undo(window, qtbot)
    assert window.doc.project == before


def test_trim_left_edge_keeps_content_in_place(window, qtbot):
    c1 = window.ids["c1"]
    rect = window.view.clip_scene_rect(c1)
    start = view_point(window, QPointF(rect.left() + 2, rect.center().y()))
    drag(window, start, start + QPoint(40, 0))
    _, trimmed = clip(window, c1)
    assert trimmed.start == pytest.approx(0.5 + 40 / PX, abs=1.5 / PX)
    assert trimmed.source_in == pytest.approx(trimmed.start - 0.5)
    assert trimmed.end == pytest.approx(1.5)


def test_shift_drag_edge_stretches(window, qtbot):
    c1 = window.ids["c1"]
    before = window.doc.project
    rect = window.view.clip_scene_rect(c1)
    start = view_point(window, QPointF(rect.right() - 2, rect.center().y()))
    drag(window, start, start + QPoint(200, 0), SHIFT)
    _, stretched = clip(window, c1)
    assert stretched.stretch == pytest.approx(2.0, abs=0.02)
    assert stretched.start == pytest.approx(0.5)
    assert stretched.source_out == pytest.approx(1.0)  # squeezed, not trimmed
    undo(window, qtbot)
    assert window.doc.project == before


def test_fade_handle_drag_sets_fade_in(window, qtbot):
    c1 = window.ids["c1"]
    before = window.doc.project
    rect = window.view.clip_scene_rect(c1)
    start = view_point(window, QPointF(rect.left() + 1, rect.top() + 3))
    drag(window, start, start + QPoint(50, 0))
    _, faded = clip(window, c1)
    assert faded.fade_in.length == pytest.approx(50 / PX, abs=2 / PX)
    assert faded.fade_out.length == 0
    undo(window, qtbot)
    assert window.doc.project == before


def test_fade_out_handle(window, qtbot):
    c1 = window.ids["c1"]
    rect = window.view.clip_scene_rect(c1)
    start = view_point(window, QPointF(rect.right() - 1, rect.top() + 3))
    drag(window, start, start - QPoint(80, 0))
    _, faded = clip(window, c1)
    assert faded.fade_out.length == pytest.approx(80 / PX, abs=2 / PX)


def test_mirror_line_then_amplitude_drag_scales_about_it(window, qtbot):
    c1 = window.ids["c1"]
    before = window.doc.project
    item = window.view.clip_item(c1)
    pivot_y = item.mapToScene(QPointF(0, item.value_y(0.5))).y()
    rect = window.view.clip_scene_rect(c1)
    QTest.mouseClick(
        window.view.viewport(),
        Qt.MouseButton.LeftButton,
        ALT,
        view_point(window, QPointF(rect.center().x(), pivot_y)),
    )
    _, placed = clip(window, c1)
    assert placed.pivot == pytest.approx(0.5, abs=0.05)
    assert placed.scale == 1.0
    start = clip_point(window, c1, 0.5, 0.5)
    half = window.view.lane_geometry.lane_height / 2 - 8
    drag(window, start, start - QPoint(0, int(half)), SHIFT)  # up by `half` doubles
    _, scaled = clip(window, c1)
    assert scaled.scale == pytest.approx(2.0, rel=0.05)
    # about the pivot p: offset = p + f*(0 - p) = p*(1 - f)
    assert scaled.offset == pytest.approx(placed.pivot * (1 - scaled.scale))
    undo(window, qtbot)
    assert window.doc.project.find_clip(c1)[1] == placed
    undo(window, qtbot)
    assert window.doc.project == before


def test_rubber_band_selects_across_tracks_and_merge_lands_in_palette(window, qtbot):
    win = window
    scratch_before = win.doc.project.tab("Scratch").tile_ids
    top_left = view_point(win, QPointF(0.2 * PX, 2))
    bottom_right = view_point(win, QPointF(2.2 * PX, 2 * win.view.lane_geometry.lane_height - 4))
    drag(win, top_left, bottom_right)
    assert set(win.doc.selected_clips) == {win.ids["c1"], win.ids["c2"]}
    QTest.keyClick(win, Qt.Key.Key_M, Qt.KeyboardModifier.ControlModifier)
    scratch = win.doc.project.tab("Scratch").tile_ids
    assert len(scratch) == len(scratch_before) + 1
    merged = win.doc.project.tile(scratch[-1])
    assert merged.duration == pytest.approx(2.5 - 0.5, abs=1e-3)
    assert win.doc.selected_tile == scratch[-1]
    undo(win, qtbot)
    assert win.doc.project.tab("Scratch").tile_ids == scratch_before
