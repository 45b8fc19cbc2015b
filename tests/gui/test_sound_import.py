"""File > Import sound as haptic, and Alt-drops: the design and the sound land in one undo step."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest
import soundfile
from PySide6.QtCore import QEvent, QMimeData, QPoint, QPointF, Qt, QUrl
from PySide6.QtGui import QDragEnterEvent, QDragMoveEvent, QDropEvent
from PySide6.QtTest import QTest
from PySide6.QtWidgets import QApplication, QFileDialog

from tests.analysis.conftest import tone_bursts
from timeline.analysis import AnalysisSettings
from timeline.analysis.source import analyse_file
from timeline.edits.vibration import VibrationTile
from timeline.files.convert import design_of_analysis
from timeline.rendering.source_sound import render_sound

from .helpers import view_point

CTRL_SHIFT = Qt.KeyboardModifier.ControlModifier | Qt.KeyboardModifier.ShiftModifier
ALT = Qt.KeyboardModifier.AltModifier
PX = 200.0
RATE = 44_100


@pytest.fixture
def bursts(tmp_path: Path) -> Path:
    path = tmp_path / "bursts.wav"
    soundfile.write(path, tone_bursts([0.1, 0.45, 0.8], 150.0, 1.2, rate=RATE), RATE, "FLOAT")
    return path


def drop_files(win, paths: list[Path], at: QPoint, modifiers) -> None:
    """Files dragged from the desktop and released on the lanes with keys held."""
    mime = QMimeData()
    mime.setUrls([QUrl.fromLocalFile(str(p)) for p in paths])
    vp = win.view.viewport()
    copy, nobutton = Qt.DropAction.CopyAction, Qt.MouseButton.NoButton
    QApplication.sendEvent(vp, QDragEnterEvent(at, copy, mime, nobutton, modifiers))
    QApplication.sendEvent(vp, QDragMoveEvent(at, copy, mime, nobutton, modifiers))
    drop = QDropEvent(QPointF(at), copy, mime, nobutton, modifiers, QEvent.Type.Drop)
    QApplication.sendEvent(vp, drop)


def test_menu_command_imports_the_design_and_the_sound(window, qtbot, monkeypatch, bursts):
    win = window
    monkeypatch.setattr(QFileDialog, "getOpenFileNames", lambda *a, **k: ([str(bursts)], ""))
    tracks_before = len(win.doc.project.tracks)
    win.view.lane_geometry.px_per_unit = 2000.0  # the view shows about half a second from 0 s
    win.view.refresh()
    QTest.keyClick(win, Qt.Key.Key_H, CTRL_SHIFT)
    qtbot.waitUntil(lambda: not win.jobs and "as haptic" in win.messages.text, timeout=20_000)
    project = win.doc.project
    assert len(project.tracks) == tracks_before + 2 and project.tracks[-1].kind == "audio"
    # the emphasis: clips of their own on a drive track just under the design's
    assert (project.tracks[1].kind, project.tracks[1].name) == ("drive", "Emphasis")
    # the cursor is at 0 s, where the first drive track's sine (0.5-1.5 s) leaves no room for
    # 1.2 s: like any import, the design, its emphasis and the sound all land at 1.5 s together
    expected = design_of_analysis(analyse_file(bursts))
    assert [c.start for c in project.tracks[1].clips] == [1.5 + e.time for e in expected.emphasis]
    sound, _ = soundfile.read(bursts)
    np.testing.assert_allclose(render_sound(project, 1.5, 2.7, RATE), sound, atol=1e-6)
    assert not render_sound(project, 0.0, 1.5, RATE).any()
    # the design is an editable envelope tile on the first drive track, after the sine
    placed = [c for c in project.tracks[0].clips if c.start == 1.5]
    tiles = [project.tile(c.tile_id) for c in placed]
    designs = [t.design for t in tiles if isinstance(t, VibrationTile)]
    assert designs == [dataclasses.replace(expected, emphasis=())]
    bar, x = win.view.horizontalScrollBar(), win.view.lane_geometry.x(1.5)
    assert bar.value() > 0 and bar.value() <= x <= bar.value() + win.view.viewport().width()
    new = [*placed, *project.tracks[1].clips, *project.tracks[-1].clips]
    assert set(win.doc.selected_clips) == {c.id for c in new}
    assert win.sound_import.dock.isVisible()
    QTest.keyClick(win, Qt.Key.Key_Z, Qt.KeyboardModifier.ControlModifier)
    assert len(win.doc.project.tracks) == tracks_before  # one step took both away
    assert not any(isinstance(t, VibrationTile) for t in win.doc.project.tiles.values())


def test_panel_settings_shape_the_design(window, qtbot, bursts):
    win = window
    panel = win.sound_import.panel
    win.sound_import.dock.show()
    sensitivity = panel.fields["sensitivity"]
    sensitivity.selectAll()
    QTest.keyClicks(sensitivity, "100")
    QTest.keyClick(sensitivity, Qt.Key.Key_Return)
    assert panel.settings().sensitivity == 100.0
    win.sound_import.convert_files([bursts], "", 0.0)
    qtbot.waitUntil(lambda: not win.jobs and "as haptic" in win.messages.text, timeout=20_000)
    assert "3 emphasis" in win.messages.text
    panel.restore_defaults()
    assert panel.settings() == AnalysisSettings()


def test_clashing_settings_are_one_sentence_in_the_panel(window, bursts):
    win = window
    panel = win.sound_import.panel
    panel.fields["frequency_min"].setValue(900.0)
    panel.fields["frequency_max"].setValue(100.0)
    before = win.doc.project
    win.sound_import.convert_files([bursts], "", 0.0)
    assert "frequency_min must be below frequency_max" in win.messages.text
    assert "frequency_min" in panel.error.text() and win.doc.project is before


def test_alt_drop_on_a_drive_lane_converts_there_or_in_the_next_gap(window, qtbot, bursts):
    win = window
    lane = win.view.lane_geometry.lane_top(1) + 30  # the second drive track: a ramp at 2.0-2.5 s
    for seconds, expected in ((3.0, 3.0), (2.0, 4.2)):  # 2.0: covered; 2.5-3.0 is too short
        drop_files(win, [bursts], view_point(win, QPointF(seconds * PX, lane)), ALT)
        qtbot.waitUntil(lambda: not win.jobs and "as haptic" in win.messages.text, timeout=20_000)
        win.messages.show_message("")
        project = win.doc.project
        placed = max(project.track(win.ids["t2"]).clips, key=lambda c: c.start)
        assert placed.start == pytest.approx(expected, abs=1 / PX)
        audio = project.tracks[-1]
        assert audio.kind == "audio" and audio.clips[0].start == placed.start


def test_plain_drop_still_imports_the_waveform(window, qtbot, bursts):
    win = window
    lane = win.view.lane_geometry.lane_top(1) + 30
    drop_files(win, [bursts], view_point(win, QPointF(2.0 * PX, lane)), Qt.KeyboardModifier(0))
    qtbot.waitUntil(lambda: not win.jobs, timeout=20_000)
    assert "imported bursts.wav" in win.messages.text
    assert all(t.kind != "audio" for t in win.doc.project.tracks)


def test_cancel_stops_the_analysis_and_changes_nothing(window, qtbot, tmp_path):
    win = window
    path = tmp_path / "long.wav"
    soundfile.write(path, np.tile(tone_bursts([0.05], 200.0, 1.0, rate=8000), 120), 8000)
    before = win.doc.project
    win.sound_import.convert_files([path], "", 0.0)
    QTest.mouseClick(win.messages.cancel, Qt.MouseButton.LeftButton)
    qtbot.waitUntil(lambda: not win.jobs, timeout=20_000)
    assert "cancelled" in win.messages.text and win.doc.project is before


def test_playing_with_a_sound_says_when_no_card_can_play_it(window, qtbot, bursts):
    win = window
    win.sound_import.convert_files([bursts], "", 0.0)
    qtbot.waitUntil(lambda: not win.jobs and "as haptic" in win.messages.text, timeout=20_000)
    QTest.keyClick(win.view, Qt.Key.Key_Space)
    qtbot.waitUntil(lambda: win.player.playing, timeout=5_000)
    if win.player.sound.playing:  # a machine with a sound card hears it
        assert win.player.sound.project is win.doc.project
    else:
        assert win.messages.text.startswith("the source sound is not played: ")
    QTest.keyClick(win.view, Qt.Key.Key_Space)
    assert not win.player.playing and not win.player.sound.playing
