"""Copy, cut and paste through the system clipboard: within and between tracks and projects."""

from __future__ import annotations

import json

import pytest
from PySide6.QtCore import QPoint, QPointF, Qt
from PySide6.QtGui import QGuiApplication
from PySide6.QtTest import QTest
from PySide6.QtWidgets import QMessageBox

from timeline import edits
from timeline.files import clipboard, projectfile
from timeline.tiles import generator

from .helpers import click, clip_point, drag, view_point

CTRL = Qt.KeyboardModifier.ControlModifier
LEFT = Qt.MouseButton.LeftButton
PX = 200.0


def ruler_click(win, u: float) -> None:
    x = round(win.view.lane_geometry.x(u) - win.view.horizontalScrollBar().value())
    QTest.mouseClick(win.ruler, LEFT, pos=QPoint(x, 30))


def all_clips(project):
    return {c.id: (t.id, c) for t in project.tracks for c in t.clips}


def test_copy_and_paste_on_the_same_track_at_the_playhead(window):
    win = window
    c1 = win.ids["c1"]
    win.doc.apply("fade", edits.set_fade, c1, "in", 0.1, "s-curve")
    win.doc.apply("gain", edits.set_clip_gain, c1, 0.5)
    click(win, clip_point(win, c1))
    QTest.keyClick(win, Qt.Key.Key_C, CTRL)
    mime = QGuiApplication.clipboard().mimeData()
    assert mime.hasFormat(clipboard.MIME)
    text = mime.text()
    assert json.loads(text)["format"] == "haptic-timeline"
    ruler_click(win, 3.0)
    tiles_before = dict(win.doc.project.tiles)
    QTest.keyClick(win, Qt.Key.Key_V, CTRL)
    [new] = win.doc.selected_clips
    track, pasted = all_clips(win.doc.project)[new]
    original = win.doc.project.find_clip(c1)[1]
    assert track == win.ids["t1"]
    assert pasted.start == pytest.approx(3.0, abs=1 / PX)
    assert pasted.tile_id == original.tile_id  # the same tile, not a copy in the palette
    assert (pasted.gain, pasted.fade_in, pasted.duration) == (
        original.gain,
        original.fade_in,
        original.duration,
    )
    assert dict(win.doc.project.tiles) == tiles_before
    assert win.doc.history.undo_label == "paste"


def test_cut_two_tracks_and_paste_keeps_their_lanes_and_offsets(window):
    win = window
    c1, c2 = win.ids["c1"], win.ids["c2"]  # 0.5 s on t1, 2.0 s on t2
    top_left = view_point(win, QPointF(0.2 * PX, 2))
    bottom_right = view_point(win, QPointF(2.8 * PX, 2 * win.view.lane_geometry.lane_height - 4))
    drag(win, top_left, bottom_right)
    assert set(win.doc.selected_clips) == {c1, c2}
    QTest.keyClick(win, Qt.Key.Key_X, CTRL)
    assert not win.doc.project.track(win.ids["t1"]).clips
    assert not win.doc.project.track(win.ids["t2"]).clips
    assert win.doc.history.undo_label == "cut"
    ruler_click(win, 1.0)
    QTest.keyClick(win, Qt.Key.Key_V, CTRL)
    t1 = win.doc.project.track(win.ids["t1"]).clips
    t2 = win.doc.project.track(win.ids["t2"]).clips
    assert [c.start for c in t1] == [pytest.approx(1.0, abs=1 / PX)]
    assert [c.start for c in t2] == [pytest.approx(2.5, abs=1 / PX)]
    QTest.keyClick(win, Qt.Key.Key_Z, CTRL)
    QTest.keyClick(win, Qt.Key.Key_Z, CTRL)
    assert win.doc.project.find_clip(c1)[1].start == 0.5


def test_paste_into_another_open_project_brings_the_tile(window, qtbot):
    from timeline.gui.main_window import MainWindow

    win = window
    c1 = win.ids["c1"]
    click(win, clip_point(win, c1))
    QTest.keyClick(win, Qt.Key.Key_C, CTRL)
    other = MainWindow()
    other.ask_unsaved = lambda: QMessageBox.StandardButton.Discard
    qtbot.addWidget(other)
    other.show()
    qtbot.waitExposed(other)
    other.activateWindow()
    qtbot.waitUntil(other.isActiveWindow)
    QTest.keyClick(other, Qt.Key.Key_V, CTRL)
    assert other.messages.text == "paste (Ctrl+Z undoes)"
    [new] = other.doc.selected_clips
    track, pasted = all_clips(other.doc.project)[new]
    assert other.doc.project.track(track).kind == "drive"
    assert other.doc.project.tile(pasted.tile_id) == win.doc.project.tile(win.ids["sine"])
    assert pasted.tile_id in other.doc.project.tab("Scratch").tile_ids
    other.player.close()
    other.autosaver.discard()


def test_json_text_from_a_script_pastes_and_junk_is_refused(window):
    win = window
    p = edits.new_project(templates=False)
    p, tile = edits.add_tile(p, generator("square", 0.25, frequency=40))
    p, track = edits.add_track(p, "stiffness")
    p, _ = edits.add_clip(p, track, tile, 0.0, gain=0.3)
    QGuiApplication.clipboard().setText(projectfile.dumps(p))
    ruler_click(win, 4.0)
    click(win, view_point(win, QPointF(3.9 * PX, 2.5 * win.view.lane_geometry.lane_height)))
    assert win.doc.selected_clips == []
    QTest.keyClick(win, Qt.Key.Key_V, CTRL)
    [new] = win.doc.selected_clips
    track_id, pasted = all_clips(win.doc.project)[new]
    assert track_id == win.ids["t3"]  # the project's stiffness track
    assert pasted.gain == 0.3
    before = win.doc.project
    QGuiApplication.clipboard().setText("not a clip")
    QTest.keyClick(win, Qt.Key.Key_V, CTRL)
    assert win.doc.project == before
    assert win.messages.text.startswith("nothing to paste: the clipboard is not a readable")
