"""The Sound analysis panel is live: a setting changed re-analyses the design as one undo step."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import soundfile
from PySide6.QtCore import Qt
from PySide6.QtTest import QTest

from tests.analysis.conftest import tone_bursts
from timeline import edits
from timeline.edits.vibration import design_of

RATE = 22_050


def emphasis_count(win) -> int:
    return sum(len(t.clips) for t in win.doc.project.tracks if t.name == "Emphasis")


def test_a_changed_setting_re_analyses_and_undo_restores(window, qtbot, tmp_path: Path) -> None:
    win = window
    path = tmp_path / "bursts.wav"
    soundfile.write(path, tone_bursts([0.1, 0.45, 0.8], 150.0, 1.2, rate=RATE), RATE, "FLOAT")
    win.sound_import.convert_files([path], "", 0.0)
    qtbot.waitUntil(lambda: not win.jobs and "as haptic" in win.messages.text, timeout=20_000)
    assert emphasis_count(win) == 3  # the three bursts, at the default sensitivity
    # staged for the default device: envelope and emphasis pulses stay within its full scale
    drive = design_of(win.doc.project).render(np.arange(0.0, 1.2, 1 / 8000))
    assert 0.9 < np.abs(drive).max() <= 1.0
    # the designer's own edit on another track, made after the import
    audio = next(t for t in win.doc.project.tracks if t.kind == "audio")
    win.doc.replace("audio gain", edits.set_track(win.doc.project, audio.id, gain=0.5))
    edited = win.doc.project
    panel = win.sound_import.panel
    win.sound_import.dock.show()
    sensitivity = panel.fields["sensitivity"]
    sensitivity.setFocus()
    sensitivity.selectAll()
    QTest.keyClicks(sensitivity, "1")  # sparse: only the strongest hit
    QTest.keyClick(sensitivity, Qt.Key.Key_Return)
    qtbot.waitUntil(lambda: "re-analysed" in win.messages.text and not win.jobs, timeout=20_000)
    assert emphasis_count(win) == 1
    assert next(t for t in win.doc.project.tracks if t.kind == "audio").gain == 0.5  # kept
    win.sound_import.dock.grab().save("/tmp/convert_dock.png")
    QTest.keyClick(win, Qt.Key.Key_Z, Qt.KeyboardModifier.ControlModifier)  # one step back
    assert win.doc.project == edited and emphasis_count(win) == 3
