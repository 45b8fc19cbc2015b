"""Tile parameters typed and dragged in the inspector: one undo step each, felt while playing."""

from __future__ import annotations

import numpy as np
import pytest
from PySide6.QtCore import QPoint, Qt
from PySide6.QtTest import QTest

from timeline import render
from timeline.plugins.track_kinds import track_kind

from .helpers import click, clip_point

CTRL = Qt.KeyboardModifier.ControlModifier
LEFT = Qt.MouseButton.LeftButton


def type_into(box, text: str) -> None:
    QTest.mouseDClick(box.lineEdit(), LEFT)
    QTest.keyClick(box, Qt.Key.Key_A, CTRL)
    QTest.keyClicks(box, text)
    QTest.keyClick(box, Qt.Key.Key_Return)


def drive(project, t: float) -> float:
    layers = render(project, t, t + 1e-4, 10_000.0)
    return float(layers["drive"][0])


def test_typing_a_template_sine_frequency_edits_a_copy_in_one_step(window):
    win = window
    c1, sine = win.ids["c1"], win.ids["sine"]
    click(win, clip_point(win, c1))
    boxes = win.inspector.boxes
    assert boxes["frequency"].value() == 5.0 and boxes["frequency"].suffix() == " Hz"
    assert boxes["length"].value() == 1.0 and boxes["length"].suffix() == " s"
    before = win.doc.project
    box = boxes["frequency"]
    type_into(box, "12")
    # the copy has the same fields: the box that was typed into lives on (deleting it from its
    # own editingFinished crashed the real window)
    assert win.inspector.boxes["frequency"] is box
    project = win.doc.project
    clip = project.find_clip(c1)[1]
    copy = project.tile(clip.tile_id)
    assert clip.tile_id != sine and clip.tile_id in project.tab("Scratch").tile_ids
    assert copy.param("frequency") == 12.0
    assert project.tile(sine).param("frequency") == 5.0  # the template is untouched
    assert win.doc.selected_tile == clip.tile_id
    # a quarter period of 12 Hz into the clip the drive is at its peak (full scale, N*m)
    full = track_kind("drive").full_scale
    assert drive(project, 0.5 + 1 / 48) == pytest.approx(full, rel=1e-6)
    assert drive(before, 0.5 + 1 / 20) == pytest.approx(full, rel=1e-6)  # 5 Hz before
    assert win.doc.history.undo_label == "set frequency"
    QTest.keyClick(win, Qt.Key.Key_Z, CTRL)
    assert win.doc.project == before


def test_dragging_a_parameter_name_scrubs_it_as_one_step(window):
    win = window
    click(win, clip_point(win, win.ids["c1"]))
    type_into(win.inspector.boxes["frequency"], "10")  # now editing a copy
    steps = len(win.doc.history)
    label = win.inspector.labels["frequency"]
    start = QPoint(10, label.height() // 2)
    QTest.mousePress(label, LEFT, pos=start)
    for dx in (5, 10, 20, 30):
        QTest.mouseMove(label, start + QPoint(dx, 0))
    QTest.mouseRelease(label, LEFT, pos=start + QPoint(30, 0))
    tile = win.doc.project.tile(win.doc.selected_tile)
    assert tile.param("frequency") == pytest.approx(40.0)  # 30 px x 1 Hz per px
    assert win.inspector.boxes["frequency"].value() == pytest.approx(40.0)
    assert len(win.doc.history) == steps + 1
    QTest.keyClick(win, Qt.Key.Key_Z, CTRL)
    assert win.doc.project.tile(win.doc.selected_tile).param("frequency") == 10.0


def test_typing_a_length_carries_the_clip_that_plays_all_of_it(window):
    win = window
    c2 = win.ids["c2"]  # the ramp template, 0.5 s at 2.0 s
    click(win, clip_point(win, c2))
    type_into(win.inspector.boxes["length"], "2")
    clip = win.doc.project.find_clip(c2)[1]
    assert clip.duration == pytest.approx(2.0)
    tile = win.doc.project.tile(clip.tile_id)
    assert tile.duration == 2.0 and tile.name == "ramp copy"
    assert clip_point(win, c2, 0.99).x() > clip_point(win, c2, 0.01).x() + 350


def test_a_parameter_edit_is_felt_while_playing(window, qtbot):
    win = window
    click(win, clip_point(win, win.ids["c1"]))
    win.transport.loop.setChecked(True)
    QTest.keyClick(win, Qt.Key.Key_Space)
    assert win.player.playing
    stream = win.player.stream
    version = stream.state.version
    loud = np.abs(stream.render(win.doc.project, 0.5, 1.5).d).max()
    assert loud > 0
    type_into(win.inspector.boxes["amplitude"], "0.25")
    assert stream.state.version == version + 1
    qtbot.waitUntil(lambda: stream.state.live_version == version + 1, timeout=15_000)
    quiet = np.abs(stream.render(win.doc.project, 0.5, 1.5).d).max()
    assert quiet == pytest.approx(0.25 * loud, rel=1e-9)
    QTest.keyClick(win, Qt.Key.Key_Space)
    assert not win.player.playing


def test_dragging_a_point_of_the_bump_template_edits_a_copy(window):
    from PySide6.QtCore import QPointF

    from timeline.gui.gestures.palette_drop import tile_mime
    from timeline.tiles import SplineTile

    from .helpers import send_drop, view_point

    win = window
    win.new_project("time")
    project = win.doc.project
    bump = next(k for k, t in project.tiles.items() if t.name == "bump")
    send_drop(win, tile_mime(bump), view_point(win, QPointF(100, 30)))
    [clip_id] = win.doc.selected_clips
    before = win.doc.project
    canvas = win.editor.canvas
    canvas.repaint()
    t, v = project.tile(bump).points[1]
    start = QPoint(round(canvas.x_of(t)), round(canvas.y_of(v)))
    QTest.mousePress(canvas, LEFT, pos=start)
    for dy in (5, 10, 20):
        QTest.mouseMove(canvas, start + QPoint(0, dy))
    QTest.mouseRelease(canvas, LEFT, pos=start + QPoint(0, 20))
    project = win.doc.project
    assert project.tile(bump) == before.tile(bump)  # the template is as it was
    copy = project.find_clip(clip_id)[1].tile_id
    assert copy != bump and copy in project.tab("Scratch").tile_ids
    tile = project.tile(copy)
    assert isinstance(tile, SplineTile) and tile.name == "bump copy"
    assert tile.points[1][1] < v  # dragged down
    assert win.messages.text.startswith("a template is never changed")
    QTest.keyClick(win, Qt.Key.Key_Z, CTRL)
    assert win.doc.project == before
