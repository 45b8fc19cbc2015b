"""Exact values typed into the inspector for a clip, a marker and a track land exactly in the
saved project (the fan knob's 20 degrees, x0.2 and settings at 50/110/170/230 degrees)."""

from __future__ import annotations

import math
import os
from pathlib import Path

import pytest
from PySide6.QtCore import QPoint, Qt
from PySide6.QtTest import QTest
from PySide6.QtWidgets import QApplication

from timeline import edits, generator, render
from timeline.edits import markers
from timeline.files import projectfile

from .helpers import click, clip_point, shown_window

LEFT = Qt.MouseButton.LeftButton
CTRL = Qt.KeyboardModifier.ControlModifier
deg = math.radians


def type_into(box, text: str) -> None:
    """Select what a box holds and type a value with Enter, as a person does."""
    QTest.mouseDClick(box.lineEdit() if hasattr(box, "lineEdit") else box, LEFT)
    QTest.keyClick(box, Qt.Key.Key_A, CTRL)
    QTest.keyClicks(box, text)
    QTest.keyClick(box, Qt.Key.Key_Return)


def rough_fan_knob():
    """The fan knob as dragged by hand: the detents at 21.087 deg, x0.157, settings off."""
    p = edits.new_project("position")
    p, torque = edits.add_track(p, "torque", "Walls and detents")
    p, detents = edits.add_tile(
        p, generator("detents", deg(240), "four detents", count=4, phase=-0.5), "Scratch"
    )
    p, clip = edits.add_clip(p, torque, detents, deg(21.087), gain=0.157)
    for name, at in (("Off", 47.3), ("Lo", 113.9), ("Med", 168.2), ("Hi", 233.3)):
        p, _ = markers.add_marker(p, deg(at), name)
    return p, torque, clip


@pytest.fixture
def knob(qtbot):
    project, torque, clip = rough_fan_knob()
    win = shown_window(qtbot, project)
    win.view.fit()
    win.ids = {"torque": torque, "clip": clip}
    yield win
    win.player.close()
    win.autosaver.discard()


def flag_point(win, index: int) -> QPoint:
    return QPoint(round(win.ruler.x_of(win.doc.project.markers[index].at)) + 2, 6)


def shot(win, name: str) -> None:
    if os.environ.get("HT_SCREENSHOTS"):
        for _ in range(2):  # fields appear, then the scroll area takes their size
            QApplication.processEvents()
        win.inspector.grab().save(str(Path(os.environ["HT_SCREENSHOTS"]) / f"{name}.png"))


def test_typed_clip_marker_and_track_values_are_saved_exactly(knob, tmp_path):
    win = knob
    clip_id = win.ids["clip"]
    click(win, clip_point(win, clip_id))
    page = win.inspector.pages["clip"]
    assert page.isVisible() and page.start.suffix() == "°"
    assert page.start.value() == pytest.approx(21.087) and page.gain.value() == 0.157
    steps = len(win.doc.history)
    type_into(page.start, "20")
    type_into(page.gain, "0.2")
    assert len(win.doc.history) == steps + 2  # one undo step each
    assert win.doc.history.undo_label == "set gain of 'four detents' to x0.2"
    assert page.db.value() == pytest.approx(20 * math.log10(0.2), abs=0.01)
    type_into(page.fade_in, "5")
    page.shape_out.setFocus()
    shape = page.shape_out.findText("s-curve")
    page.shape_out.setCurrentIndex(shape)
    page.shape_out.activated.emit(shape)
    type_into(page.fade_out, "10")
    shot(win, "ed-exact-clip")
    # leaving a box untouched (focus moves on) changes nothing
    steps = len(win.doc.history)
    page.start.setFocus()
    page.length.setFocus()
    assert len(win.doc.history) == steps
    # markers: click each flag, type its setting's angle in place
    for index, at in enumerate((50, 110, 170, 230)):
        QTest.mouseClick(win.ruler, LEFT, pos=flag_point(win, index))
        marker_page = win.inspector.pages["marker"]
        assert marker_page.isVisible() and not page.isVisible()
        type_into(marker_page.position, str(at))
    QTest.mouseClick(win.ruler, LEFT, pos=flag_point(win, 0))
    type_into(win.inspector.pages["marker"].name, "Off setting")
    shot(win, "ed-exact-marker")
    # the track: click its header, type its full scale in mNm
    header = win.headers.headers[win.ids["torque"]]
    QTest.mouseClick(header.kind, LEFT)
    track_page = win.inspector.pages["track"]
    assert track_page.isVisible() and track_page.full_scale.suffix() == " mNm"
    assert track_page.full_scale.value() == 180.0
    type_into(track_page.full_scale, "150")
    type_into(track_page.name, "Detents")
    shot(win, "ed-exact-track")

    assert win.save_to(tmp_path / "knob.htl")
    saved = projectfile.load(tmp_path / "knob.htl")
    track, clip = saved.find_clip(clip_id)
    assert clip.start == math.radians(20) and clip.gain == 0.2
    assert clip.fade_in.length == math.radians(5) and clip.fade_in.shape == "linear"
    assert clip.fade_out.length == math.radians(10) and clip.fade_out.shape == "s-curve"
    assert [m.at for m in saved.markers] == [math.radians(a) for a in (50, 110, 170, 230)]
    assert [m.name for m in saved.markers] == ["Off setting", "Lo", "Med", "Hi"]
    assert track.full_scale == 0.15 and track.name == "Detents"
    # undo walks back one typed value at a time
    QTest.keyClick(win, Qt.Key.Key_Z, CTRL)
    assert win.doc.project.tracks[0].name == "Walls and detents"


def test_a_typed_gain_in_db_and_a_stretch_are_felt_through_the_render(window):
    win = window
    c1 = win.ids["c1"]
    click(win, clip_point(win, c1))
    page = win.inspector.pages["clip"]
    assert page.start.suffix() == " s" and page.start.value() == 0.5
    before = render(win.doc.project, 0.55, 0.5501, 10_000.0)["drive"][0]
    type_into(page.db, "-6")
    after = render(win.doc.project, 0.55, 0.5501, 10_000.0)["drive"][0]
    assert after == pytest.approx(before * 10 ** (-6 / 20), rel=1e-9)
    assert page.gain.value() == pytest.approx(0.5012, abs=1e-4)
    type_into(page.stretch, "2")
    _, clip = win.doc.project.find_clip(c1)
    assert clip.stretch == 2.0 and clip.duration == 2.0 and clip.start == 0.5
    type_into(page.length, "1.25")
    assert win.doc.project.find_clip(c1)[1].end == pytest.approx(1.75, abs=1e-12)
    type_into(page.mirror, "0.5")
    assert win.doc.project.find_clip(c1)[1].pivot == 0.5
    # a refused value (a fade longer than the clip) leaves the clip and shows its value again
    type_into(page.fade_in, "9")
    assert win.doc.project.find_clip(c1)[1].fade_in.length == 0.0
    assert page.fade_in.value() == 0.0


def test_a_typed_clip_gain_is_felt_while_playing(window, qtbot):
    import numpy as np

    win = window
    click(win, clip_point(win, win.ids["c1"]))
    win.transport.loop.setChecked(True)
    QTest.keyClick(win, Qt.Key.Key_Space)
    assert win.player.playing
    stream = win.player.stream
    version = stream.state.version
    loud = np.abs(stream.render(win.doc.project, 0.5, 1.5).d).max()
    type_into(win.inspector.pages["clip"].gain, "0.2")
    assert stream.state.version == version + 1  # the same path as a drag: the stream follows
    qtbot.waitUntil(lambda: stream.state.live_version == version + 1, timeout=15_000)
    quiet = np.abs(stream.render(win.doc.project, 0.5, 1.5).d).max()
    assert quiet == pytest.approx(0.2 * loud, rel=1e-9)
    QTest.keyClick(win, Qt.Key.Key_Space)


def test_a_marker_is_renamed_in_place_on_the_ruler(knob):
    win = knob
    ruler = win.ruler
    at = flag_point(win, 1)
    QTest.mouseClick(ruler, LEFT, pos=at)  # QTest's first double-click is lost
    QTest.mouseDClick(ruler, LEFT, pos=at)
    box = ruler.name_edit
    assert box is not None and box.isVisible() and box.text() == "Lo"
    assert QApplication.activeModalWidget() is None  # no dialog
    QTest.keyClick(box, Qt.Key.Key_A, CTRL)
    QTest.keyClicks(box, "Low")
    QTest.keyClick(box, Qt.Key.Key_Return)
    assert [m.name for m in win.doc.project.markers] == ["Off", "Low", "Med", "Hi"]
    assert ruler.name_edit is None and win.doc.history.undo_label == "rename marker Lo to Low"
    # Escape leaves the name as it was
    QTest.mouseDClick(ruler, LEFT, pos=flag_point(win, 2))
    box = ruler.name_edit
    assert box is not None
    QTest.keyClicks(box, "zzz")
    QTest.keyClick(box, Qt.Key.Key_Escape)
    assert ruler.name_edit is None and win.doc.project.markers[2].name == "Med"


def test_a_scrub_let_go_while_playing_starts_the_knob_at_that_angle(knob, qtbot):
    win = knob
    ruler = win.ruler
    QTest.keyClick(win, Qt.Key.Key_Space)
    assert win.player.playing
    qtbot.waitUntil(lambda: win.player.angle is not None, timeout=15_000)
    assert abs(math.degrees(win.player.angle) - 110) > 10  # it starts at the first rest point
    start = QPoint(round(ruler.x_of(win.view.scene().playhead_u)), 30)
    end = QPoint(round(ruler.x_of(math.radians(110))), 30)
    QTest.mousePress(ruler, LEFT, pos=start)
    QTest.mouseMove(ruler, (start + end) / 2)
    QTest.mouseMove(ruler, end)
    QTest.mouseRelease(ruler, LEFT, pos=end)
    assert win.doc.project.loop is None
    qtbot.waitUntil(
        lambda: win.player.angle is not None and abs(math.degrees(win.player.angle) - 110) < 2.0,
        timeout=15_000,
    )
    QTest.keyClick(win, Qt.Key.Key_Space)
    assert not win.player.playing
