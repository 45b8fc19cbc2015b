"""Fade shapes from the handle's menu, numbers beside every drag, lane scales with units,
Edit > History, the Variants list, and imports that land where they cover nothing."""

from __future__ import annotations

import pytest
from PySide6.QtCore import QPoint, Qt
from PySide6.QtGui import QContextMenuEvent
from PySide6.QtTest import QTest
from PySide6.QtWidgets import QApplication

from timeline import edits
from timeline.gui.lane_scale import full_scale_text

from .helpers import clip_point, drag, view_point

CTRL = Qt.KeyboardModifier.ControlModifier
SHIFT = Qt.KeyboardModifier.ShiftModifier
PX = 200.0


def choose(menu, text: str) -> None:
    """Walk a shown menu with the arrow keys to an entry and press Enter."""
    texts = [a.text() for a in menu.actions() if not a.isSeparator()]
    for _ in range(texts.index(text) + 1):  # nothing is active when a menu opens
        QTest.keyClick(menu, Qt.Key.Key_Down)
    QTest.keyClick(menu, Qt.Key.Key_Return)


def right_click(win, at: QPoint) -> None:
    vp = win.view.viewport()
    event = QContextMenuEvent(QContextMenuEvent.Reason.Mouse, at, vp.mapToGlobal(at))
    QApplication.sendEvent(vp, event)


def test_a_fade_handle_menu_sets_that_fade_shape_only(window, qtbot):
    win = window
    c1 = win.ids["c1"]
    win.doc.apply("fades", edits.set_fade, c1, "in", 0.3, "linear")
    win.doc.apply("fades", edits.set_fade, c1, "out", 0.3, "linear")
    handle = win.view.clip_item(c1).mapToScene(win.view.clip_item(c1).fade_handle("in"))
    right_click(win, view_point(win, handle) + QPoint(0, 3))
    menu = win.view.menu
    assert menu.title() == "Fade-in shape"
    assert [a.text() for a in menu.actions() if a.isChecked()] == ["linear"]
    qtbot.waitUntil(menu.isVisible)
    choose(menu, "s-curve")
    clip = win.doc.project.find_clip(c1)[1]
    assert (clip.fade_in.shape, clip.fade_out.shape) == ("s-curve", "linear")
    assert clip.fade_in.length == pytest.approx(0.3)
    assert win.doc.history.undo_label == "fade-in shape"


def test_every_drag_shows_its_numbers(window):
    win = window
    c1 = win.ids["c1"]  # 0.5 .. 1.5 s, drawn 200 px wide
    view = win.view
    seen: list[str] = []
    original = view.show_readout
    view.show_readout = lambda text, pos: (seen.append(text), original(text, pos))
    start = clip_point(win, c1)
    drag(win, start, start + QPoint(100, 0))
    assert seen[-1] == "start 1 s on Drive 1"
    assert not view.readout.isVisible()  # gone once the drag ends
    right = clip_point(win, c1, 0.995)
    drag(win, right, right + QPoint(100, 0), SHIFT)
    assert seen[-1] == "stretch x1.500 (squeeze), length 1.5 s"
    middle = clip_point(win, c1, 0.5)
    drag(win, middle, middle + QPoint(0, -30), SHIFT)  # up by one half-lane: x2
    assert seen[-1].startswith("amplitude +6.0 dB (x2)")
    left = clip_point(win, c1, 0.002)
    drag(win, left, left + QPoint(40, 0))
    assert seen[-1] == "start 1.2 s, length 1.3 s"
    handle = view.clip_item(c1).mapToScene(view.clip_item(c1).fade_handle("in"))
    at = view_point(win, handle) + QPoint(0, 3)
    drag(win, at, at + QPoint(20, 0))
    assert seen[-1] == "fade in 0.1 s (linear)"


def test_lanes_and_the_waveform_editor_have_scales_in_the_tracks_units(window):
    win = window
    project = win.doc.project
    drive, stiffness = project.track(win.ids["t1"]), project.track(win.ids["t3"])
    assert full_scale_text(drive, 1.0) == "+180 mNm"
    assert full_scale_text(drive, -1.0) == "-180 mNm"
    assert full_scale_text(stiffness, 1.0).endswith(stiffness_unit())
    QTest.mouseClick(
        win.view.viewport(), Qt.MouseButton.LeftButton, pos=clip_point(win, win.ids["c1"])
    )
    assert win.editor.track().id == win.ids["t1"]
    image = win.view.viewport().grab().toImage()
    lane_zero = win.view.mapFromScene(0, win.view.lane_geometry.lane_height / 2).y()
    assert image.pixelColor(3, lane_zero).lightness() < 200  # the scale's "0" label is drawn


def stiffness_unit() -> str:
    from timeline.plugins.track_kinds import track_kind

    return track_kind("stiffness").display_unit


def test_history_menu_jumps_to_a_named_step(window, qtbot):
    win = window
    c1 = win.ids["c1"]
    start = clip_point(win, c1)
    drag(win, start, start + QPoint(100, 0))
    QTest.keyClick(win, Qt.Key.Key_R, CTRL)  # reverse
    QTest.keyClick(win, Qt.Key.Key_D, CTRL)  # duplicate
    assert win.doc.history.labels[-3:] == ["move clip", "reverse", "duplicate"]
    menu = win.history_menu
    menu.popup(win.mapToGlobal(QPoint(40, 40)))
    qtbot.waitUntil(menu.isVisible)
    texts = [a.text() for a in menu.actions()]
    assert texts[:4] == [  # each step named by what it changed, in seconds
        "3. duplicate 'sine' at 2 s on 'Drive 1'",
        "2. reverse 'sine'",
        "1. move 'sine' to 1 s",
        "0. open",
    ]
    assert [a.text() for a in menu.actions() if a.isChecked()] == [texts[0]]
    choose(menu, "1. move 'sine' to 1 s")
    assert win.messages.text == "back to step 1: move 'sine' to 1 s"
    clip = win.doc.project.find_clip(c1)[1]
    assert clip.start == pytest.approx(1.0) and not clip.reverse
    assert len(win.doc.project.track(win.ids["t1"]).clips) == 1
    QTest.keyClick(win, Qt.Key.Key_Z, CTRL | SHIFT)  # redo goes forward from there
    assert win.doc.project.find_clip(c1)[1].reverse


def test_variants_menu_lists_them_and_marks_the_active_one(window, qtbot):
    win = window
    QTest.keyClick(win, Qt.Key.Key_V, CTRL | SHIFT)  # save A
    win.doc.apply("gain", edits.set_clip_gain, win.ids["c1"], 0.5)
    QTest.keyClick(win, Qt.Key.Key_V, CTRL | SHIFT)  # save B
    menu = win.variants_menu
    menu.popup(win.mapToGlobal(QPoint(40, 40)))
    qtbot.waitUntil(menu.isVisible)
    listed = [a for a in menu.actions() if a.property("variant")]
    assert [a.text() for a in listed] == ["Variant A", "Variant B"]
    assert [a.text() for a in listed if a.isChecked()] == ["Variant B"]
    choose(menu, "Variant A")
    assert win.doc.project.active_variant == "A"
    assert win.doc.project.find_clip(win.ids["c1"])[1].gain == 1.0


def test_an_import_lands_on_the_selected_clips_track_where_it_covers_nothing(
    window, qtbot, tmp_path
):
    import wave

    import numpy as np

    win = window
    rate = 8000
    tone = 0.5 * np.sin(2 * np.pi * 50 * np.arange(int(0.4 * rate)) / rate)
    with wave.open(str(tmp_path / "piece.wav"), "wb") as out:
        out.setnchannels(1)
        out.setsampwidth(2)
        out.setframerate(rate)
        out.writeframes((tone * 32767).astype("<i2").tobytes())
    QTest.mouseClick(
        win.view.viewport(), Qt.MouseButton.LeftButton, pos=clip_point(win, win.ids["c1"], 0.25)
    )
    assert win.view.scene().cursor_u == pytest.approx(0.75, abs=1 / PX)  # inside the sine
    win.view.lane_geometry.px_per_unit = 2000.0  # the view shows about half a second
    win.view.refresh()
    win.view.horizontalScrollBar().setValue(0)
    win.import_files([tmp_path / "piece.wav"], win.import_track(), win.arrange.here())
    qtbot.waitUntil(lambda: not win.jobs, timeout=10_000)
    assert win.messages.text.startswith("imported piece.wav"), win.messages.history
    clips = win.doc.project.track(win.ids["t1"]).clips
    assert len(clips) == 2
    new = next(c for c in clips if c.id != win.ids["c1"])
    assert new.start == pytest.approx(1.5)  # after the sine, not on top of it
    assert new.duration == pytest.approx(0.4)
    bar, x = win.view.horizontalScrollBar(), win.view.lane_geometry.x(1.5)  # the view went to it
    assert bar.value() > 0 and bar.value() <= x <= bar.value() + win.view.viewport().width()
