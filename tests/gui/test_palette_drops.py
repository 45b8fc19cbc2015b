"""Drags between the waveform editor, the palette and the lanes, delivered as the drag events Qt
sends (a QDrag's own loop cannot run offscreen), carrying the mime data each source makes; and
tiles renamed in place in the palette."""

from __future__ import annotations

import math

import pytest
from PySide6.QtCore import QEvent, QMimeData, QPoint, QPointF, Qt
from PySide6.QtGui import QDragEnterEvent, QDragMoveEvent, QDropEvent
from PySide6.QtTest import QTest
from PySide6.QtWidgets import QApplication, QLineEdit, QWidget

from timeline import edits, generator
from timeline.gui.waveform_editor import range_mime
from timeline.tiles import SampledTile, SplineTile

from .helpers import send_drop, view_point

NO = Qt.KeyboardModifier.NoModifier
LEFT = Qt.MouseButton.LeftButton


def drag_over(widget: QWidget, mime: QMimeData, at: QPoint) -> bool:
    """Enter, move and drop on a widget as Qt does; returns whether the enter was accepted."""
    copy, none = Qt.DropAction.CopyAction, Qt.MouseButton.NoButton
    enter = QDragEnterEvent(at, copy, mime, none, NO)
    QApplication.sendEvent(widget, enter)
    if not enter.isAccepted():
        return False
    QApplication.sendEvent(widget, QDragMoveEvent(at, copy, mime, none, NO))
    drop = QDropEvent(QPointF(at), copy, mime, none, NO, QEvent.Type.Drop)
    QApplication.sendEvent(widget, drop)
    return drop.isAccepted()


def add_spline(win) -> str:
    spline = SplineTile(((0.0, 0.0), (0.5, 1.0), (1.0, 0.0)), 1.0, name="bump")
    project, tile_id = edits.add_tile(win.doc.project, spline)
    win.doc.replace("add spline", project)
    win.doc.select_tile(tile_id)
    return tile_id


def shift_select(canvas, a: float, b: float) -> None:
    """Shift-drag a range on the waveform editor's curve, as a person selects one."""
    y = canvas.height() // 2
    start, end = QPoint(int(canvas.x_of(a)), y), QPoint(int(canvas.x_of(b)), y)
    QTest.mousePress(canvas, LEFT, Qt.KeyboardModifier.ShiftModifier, start)
    QTest.mouseMove(canvas, end)
    QTest.mouseRelease(canvas, LEFT, Qt.KeyboardModifier.ShiftModifier, end)


def test_a_range_dragged_onto_a_palette_tab_becomes_a_tile_there(window):
    win = window
    tile_id = add_spline(win)
    shift_select(win.editor.canvas, 0.25, 0.75)
    a, b = win.editor.range
    assert (a, b) == (pytest.approx(0.25, abs=0.01), pytest.approx(0.75, abs=0.01))
    palette = win.tile_palette
    palette.add_tab()
    tab = palette.current_tab()
    tiles = palette.tile_list(tab)
    assert tiles.viewport().acceptDrops()
    mime = range_mime(tile_id, a, b)  # what the curve's drag carries
    assert drag_over(tiles.viewport(), mime, QPoint(20, 20))
    project = win.doc.project
    [new] = project.tab(tab).tile_ids
    tile = project.tile(new)
    assert tile.duration == pytest.approx(b - a)
    assert tile.name == f"bump {a:.4g}-{b:.4g} s"
    assert win.doc.history.undo_label == "range to palette"
    # something else (plain text) is refused
    text = QMimeData()
    text.setText("hello")
    assert not drag_over(tiles.viewport(), text, QPoint(20, 20))


def test_a_position_range_is_named_in_degrees():
    from timeline.edits import tile_shape

    p = edits.new_project("position")
    p, detents = edits.add_tile(p, generator("detents", math.radians(240), "four detents"))
    p, tile_id = tile_shape.range_to_palette(p, detents, math.radians(20), math.radians(200))
    assert p.tile(tile_id).name == "four detents 20-200 deg"
    p, again = tile_shape.range_to_palette(p, detents, math.radians(20), math.radians(200))
    assert p.tile(again).name == "four detents 20-200 deg 2"


def test_a_palette_tile_dropped_on_the_waveform_editor_opens_there(window):
    win = window
    ramp = win.ids["ramp"]
    tiles = win.tile_palette.tile_list("Templates")
    item = next(tiles.item(i) for i in range(tiles.count()) if tiles.item(i).data(256) == ramp)
    mime = tiles.mimeData([item])  # what the palette's drag carries
    steps = len(win.doc.history)
    assert drag_over(win.editor, mime, QPoint(100, 60))
    assert win.editor.tile_id == ramp and win.doc.selected_tile == ramp
    assert len(win.doc.history) == steps  # opening a tile is not an edit
    # the same drag onto a lane places a clip there
    lane = win.view.lane_geometry.lane_top(1) + 30
    send_drop(win, mime, view_point(win, QPointF(3.0 * 200, lane)))
    track = win.doc.project.tracks[1]
    [placed] = [c for c in track.clips if c.start == pytest.approx(3.0, abs=1 / 200)]
    assert placed.tile_id == ramp


def test_a_tile_dragged_onto_another_tab_is_shown_there_too(window):
    win = window
    palette = win.tile_palette
    palette.add_tab()
    tab = palette.current_tab()
    scratch = palette.tile_list("Templates")
    mime = scratch.mimeData([scratch.item(0)])
    target = palette.tile_list(tab)
    assert drag_over(target.viewport(), mime, QPoint(10, 10))
    assert win.doc.project.tab(tab).tile_ids == (scratch.item(0).data(256),)


def rename_in_place(tiles, item, name: str, by_key: bool) -> None:
    tiles.setCurrentItem(item)
    if by_key:
        tiles.setFocus()
        QTest.keyClick(tiles, Qt.Key.Key_F2)
    else:
        at = tiles.visualItemRect(item).center()
        QTest.mouseClick(tiles.viewport(), LEFT, NO, at)  # QTest's first double-click is lost
        QTest.mouseDClick(tiles.viewport(), LEFT, NO, at)
    box = tiles.findChild(QLineEdit)
    assert box is not None and box.isVisible()
    QTest.keyClick(box, Qt.Key.Key_A, Qt.KeyboardModifier.ControlModifier)
    QTest.keyClicks(box, name)
    QTest.keyClick(box, Qt.Key.Key_Return)


@pytest.mark.parametrize("by_key", [True, False])
def test_a_tile_is_renamed_in_place_with_f2_or_a_double_click(window, qtbot, by_key):
    win = window
    project, tile_id = edits.add_tile(win.doc.project, SampledTile([0.0, 1.0, 0.0], 10.0, "rec"))
    win.doc.replace("add", project)
    tiles = win.tile_palette.tile_list("Scratch")
    bar = win.tile_palette.tabs.tabBar()
    QTest.mouseClick(bar, LEFT, NO, bar.tabRect(1).center())  # the Scratch tab
    assert win.tile_palette.current_tab() == "Scratch"
    item = next(tiles.item(i) for i in range(tiles.count()) if tiles.item(i).data(256) == tile_id)
    rename_in_place(tiles, item, "knock", by_key)
    # the item view commits a typed name on its next event-loop turn
    qtbot.waitUntil(lambda: win.doc.project.tile(tile_id).name == "knock", timeout=5_000)
    assert win.doc.history.undo_label == "rename tile rec to knock"
    tiles = win.tile_palette.tile_list("Scratch")
    assert any(tiles.item(i).text() == "knock" for i in range(tiles.count()))
    QTest.keyClick(win, Qt.Key.Key_Z, Qt.KeyboardModifier.ControlModifier)
    assert win.doc.project.tile(tile_id).name == "rec"


def test_template_names_stay_and_copies_get_unique_names(window):
    win = window
    templates = win.tile_palette.tile_list("Templates")
    assert not templates.item(0).flags() & Qt.ItemFlag.ItemIsEditable
    from timeline.edits import tile_params

    sine = win.ids["sine"]
    project, first = tile_params.editable(win.doc.project, sine, [])
    project, second = tile_params.editable(project, sine, [])
    assert (project.tile(first).name, project.tile(second).name) == ("sine copy", "sine copy 2")
