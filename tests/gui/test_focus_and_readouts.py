"""Keys act on the region that has focus; the ruler, templates and readouts say what is true."""

from __future__ import annotations

import pytest
from PySide6.QtCore import QPoint, Qt
from PySide6.QtTest import QTest

from timeline.tiles import SplineTile

from .helpers import click, clip_point

LEFT = Qt.MouseButton.LeftButton


def template_names(project) -> list[str]:
    tab = next(t for t in project.palette if t.name == "Templates")
    return [project.tiles[t].name for t in tab.tile_ids]


def test_delete_removes_the_spline_point_when_the_curve_has_focus(window, qtbot):
    win = window
    c1 = win.ids["c1"]
    click(win, clip_point(win, c1))
    assert win.doc.selected_clips == [c1]
    QTest.mouseClick(win.editor.copy_button, LEFT)
    tile = win.editor.tile
    assert isinstance(tile, SplineTile)
    count = len(tile.points)
    canvas = win.editor.canvas
    canvas.repaint()
    t, v = tile.points[3]
    QTest.mouseClick(canvas, LEFT, pos=QPoint(round(canvas.x_of(t)), round(canvas.y_of(v))))
    assert win.editor.point == 3
    assert win.doc.selected_clips == [c1]  # the clip is still selected in the timeline
    QTest.keyClick(canvas, Qt.Key.Key_Delete)
    assert len(win.editor.tile.points) == count - 1
    assert win.doc.project.find_clip(c1)[1].id == c1  # the clip was not deleted
    # with the palette focused, Delete leaves the clips alone and says why
    tiles = win.tile_palette.tabs.currentWidget()
    first = tiles.visualItemRect(tiles.item(0)).center()
    QTest.mouseClick(tiles.viewport(), LEFT, pos=first)
    assert tiles.hasFocus()
    QTest.keyClick(tiles, Qt.Key.Key_Delete)
    assert win.doc.project.find_clip(c1)[1].id == c1
    assert win.messages.text.startswith("Delete removes clips when the timeline has focus")
    # with the timeline focused, Delete removes the selected clip
    click(win, clip_point(win, c1))
    assert win.view.hasFocus()
    QTest.keyClick(win.view.viewport(), Qt.Key.Key_Delete)
    assert c1 not in {c.id for t in win.doc.project.tracks for c in t.clips}


def test_ruler_click_moves_the_playhead_and_its_readout(window):
    win = window
    x = round(win.view.lane_geometry.x(1.25) - win.view.horizontalScrollBar().value())
    QTest.mouseClick(win.ruler, LEFT, pos=QPoint(x, 10))
    assert win.view.scene().playhead_u == pytest.approx(1.25, abs=1 / 200)
    assert win.transport.where.text() == f"{win.view.scene().playhead_u:.3f} s"
    assert win.transport.where.text() != "0.000 s"


@pytest.mark.parametrize("axis", ["time", "position"])
def test_a_new_project_lists_each_template_once(window, tmp_path, axis):
    from timeline.files import projectfile
    from timeline.tiles.templates import template_tiles

    win = window
    if axis == "time":
        QTest.keyClick(win, Qt.Key.Key_N, Qt.KeyboardModifier.ControlModifier)
    else:
        win.new_project(axis)
    names = template_names(win.doc.project)
    assert names == [t.name for t in template_tiles(axis)]
    assert len(set(names)) == len(names)
    assert win.save_to(tmp_path / "new.htl")
    again = projectfile.load(tmp_path / "new.htl")
    assert template_names(again) == names
    assert len(again.tiles) == len(names)


def test_a_new_project_starts_with_the_playhead_at_zero(window):
    win = window
    x = round(win.view.lane_geometry.x(2.0) - win.view.horizontalScrollBar().value())
    QTest.mouseClick(win.ruler, LEFT, pos=QPoint(x, 10))
    assert win.transport.where.text() != "0.000 s"
    win.new_project("position")
    assert win.view.scene().playhead_u == 0.0 and win.view.scene().cursor_u == 0.0
    assert win.transport.where.text() == "0.0°"


def test_a_dropped_tile_comes_up_in_the_waveform_editor_and_inspector(window):
    from PySide6.QtCore import QPointF

    from timeline.gui.gestures.palette_drop import tile_mime

    from .helpers import send_drop, view_point

    win = window
    ramp = win.ids["ramp"]
    send_drop(win, tile_mime(ramp), view_point(win, QPointF(3.0 * 200, 30)))
    assert win.doc.selected_tile == ramp
    assert win.editor.tile_id == ramp
    assert set(win.inspector.boxes) == {"length", "start", "end"}
