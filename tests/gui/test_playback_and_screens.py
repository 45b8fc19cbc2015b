"""Playing on the sim follows edits live (time and position projects); screenshots to look at."""

from __future__ import annotations

import math
from pathlib import Path

import pytest
from PySide6.QtCore import Qt
from PySide6.QtTest import QTest
from PySide6.QtWidgets import QMessageBox

from timeline import edits
from timeline.tiles import generator

ROOT = Path(__file__).resolve().parents[2]
OUT = ROOT / "test-output" / "gui"


def test_space_plays_on_the_sim_and_the_scope_fills(window, qtbot):
    win = window
    win.transport.loop.setChecked(True)
    QTest.keyClick(win, Qt.Key.Key_Space)
    assert win.player.playing
    qtbot.waitUntil(lambda: win.transport.scope.tau.size > 20, timeout=5000)
    stream = win.player.stream
    version = stream.state.version
    win.doc.apply("gain", edits.set_clip_gain, win.ids["c1"], 0.5)
    assert stream.state.version == version + 1
    qtbot.waitUntil(lambda: stream.state.live_version == version + 1, timeout=2000)
    QTest.keyClick(win, Qt.Key.Key_Space)
    assert not win.player.playing


def test_the_editor_fits_a_1280_by_800_screen(window):
    window.resize(1280, 800)
    assert (window.width(), window.height()) == (1280, 800)


def test_the_editor_opens_inside_a_1280_by_800_screen(window):
    """Opened on a laptop, the window is shrunk from its 1400x860 default to the free area."""
    from PySide6.QtCore import QRect

    from timeline.gui.app import fit_to_screen

    window.resize(1400, 860)
    fit_to_screen(window, QRect(0, 24, 1280, 776))  # below a 24-pixel top panel
    assert (window.x(), window.y(), window.width(), window.height()) == (0, 24, 1280, 776)
    fit_to_screen(window, QRect(0, 0, 640, 480))  # smaller than the editor can be
    assert window.width() == window.minimumSizeHint().width() > 640


@pytest.mark.parametrize("name", ["fan_knob", "notification_buzz"])
def test_screenshot(qtbot, name):
    from timeline.gui.main_window import MainWindow

    win = MainWindow()
    qtbot.addWidget(win)
    win.resize(1400, 860)
    win.show()
    qtbot.waitExposed(win)
    assert win.open_path(ROOT / "projects" / f"{name}.htl")
    assert win.messages.text == f"opened {name}.htl"
    first = win.doc.project.tracks[0].clips[0]
    win.doc.select_clips([first.id])
    win.doc.select_tile(first.tile_id)
    qtbot.wait(100)  # let the rebuilt track headers show, as the event loop would
    OUT.mkdir(parents=True, exist_ok=True)
    path = OUT / f"{name}.png"
    assert win.grab().save(str(path))
    assert path.stat().st_size > 10_000
    win.player.close()


def test_position_playback_follows_edits_live(qtbot):
    from timeline.gui.main_window import MainWindow

    project = edits.new_project("position")
    project, tile = edits.add_tile(project, generator("constant", 2 * math.pi), "Scratch")
    project, track = edits.add_track(project, "torque")
    project, clip = edits.add_clip(project, track, tile, 0.0, gain=0.25)  # 0.25 x 180 mNm
    win = MainWindow(project)
    win.ask_unsaved = lambda: QMessageBox.StandardButton.Discard
    qtbot.addWidget(win)
    win.show()
    qtbot.waitExposed(win)
    scope = win.transport.scope
    QTest.mouseClick(win.transport.play_button, Qt.MouseButton.LeftButton)
    assert win.player.playing
    qtbot.waitUntil(
        lambda: scope.tau.size > 5 and scope.tau[-1] == pytest.approx(45.0), timeout=5000
    )
    win.doc.apply("gain", edits.set_clip_gain, clip, 0.5)
    qtbot.waitUntil(lambda: scope.tau[-1] == pytest.approx(90.0), timeout=1500)
    win.doc.apply("remove", edits.remove_clips, [clip])
    qtbot.waitUntil(lambda: scope.tau[-1] == pytest.approx(0.0, abs=1e-9), timeout=1500)
    win.player.close()
