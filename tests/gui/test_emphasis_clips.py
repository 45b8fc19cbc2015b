"""Emphasis as clips a designer drags on the timeline: the export follows the edit."""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest
from PySide6.QtCore import QPoint, Qt
from PySide6.QtTest import QTest

from timeline import edits
from timeline.vibration import Emphasis, VibrationDesign, place_design

from .helpers import clip_point, drag

PX = 200.0  # pixels per second
DESIGN = VibrationDesign(
    amplitude=((0.0, 0.0), (0.05, 0.5), (0.9, 0.3), (1.2, 0.0)),
    frequency=((0.0, 0.4), (1.2, 0.6)),
    emphasis=(Emphasis(0.3, 0.9, 0.8), Emphasis(0.7, 0.6, 0.1)),
    duration=1.2,
)


@pytest.fixture
def designer(qtbot):
    """The editor on a project holding DESIGN, at 200 px per second, snapping off."""
    from PySide6.QtWidgets import QMessageBox

    from timeline.gui.main_window import MainWindow

    win = MainWindow(place_design(edits.new_project(), DESIGN))
    win.ask_unsaved = lambda: QMessageBox.StandardButton.Discard
    qtbot.addWidget(win)
    win.resize(1300, 700)
    win.show()
    qtbot.waitExposed(win)
    win.view.geometry.px_per_unit = PX
    win.view.snapping = False
    win.view.refresh()
    yield win
    win.player.close()
    win.autosaver.discard()


def _haptic_emphasis(win, qtbot, path: Path) -> list[tuple[float, float, float]]:
    """Export the project as .haptic through the editor; the file's (time, amplitude, freq)."""
    win.export_to(path)
    qtbot.waitUntil(lambda: not win.jobs, timeout=20_000)
    doc = json.loads(path.read_text())
    return [
        (b["time"], b["emphasis"]["amplitude"], b["emphasis"]["frequency"])
        for b in doc["signals"]["continuous"]["envelopes"]["amplitude"]
        if "emphasis" in b
    ]


def test_dragging_an_emphasis_clip_moves_the_exported_emphasis(designer, qtbot, tmp_path):
    win = designer
    accents = win.doc.project.tracks[1]
    assert accents.name == "Emphasis" and len(accents.clips) == 2
    before = _haptic_emphasis(win, qtbot, tmp_path / "before.haptic")
    assert before == [(0.3, 0.9, 0.8), (0.7, 0.6, 0.1)]
    if os.environ.get("HT_SCREENSHOTS"):
        win.grab().save(str(Path(os.environ["HT_SCREENSHOTS"]) / "emphasis_before.png"))
    first = accents.clips[0].id
    assert accents.clips[0].duration * PX == pytest.approx(2.0)  # 10 ms: 2 px at this zoom
    start = clip_point(win, first) + QPoint(3, 0)  # beside it, within its grab area
    drag(win, start, start + QPoint(round(0.1 * PX), 0))  # 20 px: 100 ms later
    moved = win.doc.project.find_clip(first)[1]
    assert moved.start == pytest.approx(0.4, abs=0.5 / PX)
    after = _haptic_emphasis(win, qtbot, tmp_path / "after.haptic")
    assert after[0][0] - before[0][0] == pytest.approx(0.1, abs=0.5 / PX)
    assert after[0][1:] == before[0][1:] and after[1] == before[1]
    # the pressed clip's tile is in the inspector: type a softer level for this emphasis
    box = win.inspector.boxes["amplitude"]
    assert box.value() == pytest.approx(0.9) and box.suffix() == " (0..1)"
    box.selectAll()
    QTest.keyClicks(box, "0.5")
    QTest.keyClick(box, Qt.Key.Key_Return)
    qtbot.wait(50)
    if os.environ.get("HT_SCREENSHOTS"):
        win.grab().save(str(Path(os.environ["HT_SCREENSHOTS"]) / "emphasis_after.png"))
    softer = _haptic_emphasis(win, qtbot, tmp_path / "softer.haptic")
    assert softer[0] == (after[0][0], 0.5, 0.8) and softer[1] == before[1]
