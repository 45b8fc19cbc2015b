"""Emphasis as clips a designer drags on the timeline: the export follows the edit."""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest
from PySide6.QtCore import QPoint, Qt
from PySide6.QtTest import QTest

from timeline import edits
from timeline.edits import vibration
from timeline.edits.vibration import Emphasis, VibrationDesign, place_design

from .helpers import choose, click, clip_point, drag

PX = 200.0  # pixels per second
DESIGN = VibrationDesign(
    amplitude=((0.0, 0.0), (0.05, 0.5), (0.9, 0.3), (1.2, 0.0)),
    frequency=((0.0, 0.4), (0.6, 0.3), (1.2, 0.6)),
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
    win.view.lane_geometry.px_per_unit = PX
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


def test_dragging_an_amplitude_breakpoint_in_the_waveform_editor_edits_the_design(
    designer, qtbot, tmp_path
):
    win = designer
    envelopes = win.doc.project.tracks[0].clips[0]
    click(win, clip_point(win, envelopes.id))  # select the clip: its tile opens in the editor
    canvas = win.editor.canvas
    assert win.editor.tile.design.amplitude == DESIGN.amplitude
    # the breakpoint at 0.9 s (0.3) dragged up to about 0.6; the drag also moves it in time a bit
    press = QPoint(int(canvas.x_of(0.9)), int(canvas.y_of(0.3)))
    target = QPoint(press.x(), int(canvas.y_of(0.6)))
    QTest.mousePress(canvas, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, press)
    QTest.mouseMove(canvas, (press + target) / 2)
    QTest.mouseMove(canvas, target)
    QTest.mouseRelease(canvas, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, target)
    if os.environ.get("HT_SCREENSHOTS"):
        win.grab().save(str(Path(os.environ["HT_SCREENSHOTS"]) / "envelope_point.png"))
    win.export_to(tmp_path / "edited.haptic")
    qtbot.waitUntil(lambda: not win.jobs, timeout=20_000)
    doc = json.loads((tmp_path / "edited.haptic").read_text())
    amplitude = [
        (b["time"], b["amplitude"])
        for b in doc["signals"]["continuous"]["envelopes"]["amplitude"]
        if "emphasis" not in b  # breakpoints the writer inserts to carry an emphasis
    ]
    moved = amplitude[2]
    assert moved[0] == pytest.approx(0.9, abs=2 * DESIGN.duration / canvas.width())
    assert moved[1] == pytest.approx(0.6, abs=0.02)
    assert [amplitude[k] for k in (0, 1, 3)] == [DESIGN.amplitude[k] for k in (0, 1, 3)]
    # dragged above full scale, an amplitude stops at 1; one undo step puts it back. Pressed
    # where the point is drawn now (the export's message may have resized the editor)
    t, v = win.editor.tile.design.amplitude[2]
    target = QPoint(round(canvas.x_of(t)), round(canvas.y_of(v)))
    QTest.mousePress(canvas, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, target)
    QTest.mouseMove(canvas, QPoint(target.x(), 0))
    QTest.mouseRelease(
        canvas, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, QPoint(target.x(), 0)
    )
    assert win.editor.tile.design.amplitude[2][1] == 1.0
    QTest.keyClick(win, Qt.Key.Key_Z, Qt.KeyboardModifier.ControlModifier)
    assert win.editor.tile.design.amplitude[2][1] == pytest.approx(0.6, abs=0.02)


def _drag_on(canvas, press: QPoint, target: QPoint) -> None:
    """Press, move in two steps and release on the waveform editor's curve."""
    QTest.mousePress(canvas, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, press)
    QTest.mouseMove(canvas, (press + target) / 2)
    QTest.mouseMove(canvas, target)
    QTest.mouseRelease(canvas, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, target)


def test_the_frequency_envelope_is_edited_in_its_own_lane_with_its_hz(designer, qtbot, tmp_path):
    win = designer
    envelopes = win.doc.project.tracks[0].clips[0]
    click(win, clip_point(win, envelopes.id))
    editor, canvas = win.editor, win.editor.canvas
    assert editor.lane_box.isVisible() and editor.lane == "amplitude"
    choose(qtbot, editor.lane_box, "Frequency")
    win.activateWindow()  # the list that popped up had it; the window's shortcuts need it back
    qtbot.waitUntil(win.isActiveWindow, timeout=5_000)
    assert editor.points() == DESIGN.frequency
    # the breakpoint at 0.6 s (0.3 = 125 Hz) dragged up to 0.6 (170 Hz): one undo step
    press = QPoint(int(canvas.x_of(0.6)), int(canvas.y_of(0.3)))
    target = QPoint(press.x(), int(canvas.y_of(0.6)))
    _drag_on(canvas, press, target)
    if os.environ.get("HT_SCREENSHOTS"):
        win.grab().save(str(Path(os.environ["HT_SCREENSHOTS"]) / "frequency_point.png"))
    t, f = editor.tile.design.frequency[1]
    assert f == pytest.approx(0.6, abs=0.02) and t == pytest.approx(0.6, abs=0.01)
    assert editor.v_box.value() == pytest.approx(f, abs=1e-4)
    assert editor.hz_label.text() == f"= {80.0 + 150.0 * f:.1f} Hz"
    assert editor.tile.design.amplitude == DESIGN.amplitude
    win.export_to(tmp_path / "sharper.haptic")
    qtbot.waitUntil(lambda: not win.jobs, timeout=20_000)
    doc = json.loads((tmp_path / "sharper.haptic").read_text())
    frequency = [
        (b["time"], b["frequency"]) for b in doc["signals"]["continuous"]["envelopes"]["frequency"]
    ]
    assert frequency[0] == DESIGN.frequency[0] and frequency[-1] == DESIGN.frequency[-1]
    assert frequency[1] == pytest.approx((0.6, 0.6), abs=0.02)
    # the exact value typed into the point's box, with the carrier it means
    editor.v_box.selectAll()
    QTest.keyClicks(editor.v_box, "0.25")
    QTest.keyClick(editor.v_box, Qt.Key.Key_Return)
    assert editor.tile.design.frequency[1] == (t, 0.25)
    assert editor.hz_label.text() == "= 117.5 Hz"
    # a double-click adds a point to the frequency envelope; Delete takes it away again
    QTest.mouseDClick(
        canvas,
        Qt.MouseButton.LeftButton,
        Qt.KeyboardModifier.NoModifier,
        QPoint(int(canvas.x_of(1.0)), int(canvas.y_of(0.9))),
    )
    assert len(editor.tile.design.frequency) == 4 and editor.point == 2
    assert editor.tile.design.frequency[2][1] == pytest.approx(0.9, abs=0.02)
    QTest.keyClick(canvas, Qt.Key.Key_Delete)
    assert len(editor.tile.design.frequency) == 3
    QTest.keyClick(win, Qt.Key.Key_Z, Qt.KeyboardModifier.ControlModifier)  # the delete
    QTest.keyClick(win, Qt.Key.Key_Z, Qt.KeyboardModifier.ControlModifier)  # the add
    QTest.keyClick(win, Qt.Key.Key_Z, Qt.KeyboardModifier.ControlModifier)  # the typed value
    QTest.keyClick(win, Qt.Key.Key_Z, Qt.KeyboardModifier.ControlModifier)  # the whole drag
    assert editor.tile.design.frequency == DESIGN.frequency


def _starts(win) -> tuple[list[float], list[float]]:
    """Clip starts on the design's track and on its Emphasis track."""
    design, accents = win.doc.project.tracks[:2]
    return [c.start for c in design.clips], [c.start for c in accents.clips]


def test_dragging_the_design_clip_takes_its_emphasis_along_in_one_undo_step(
    designer, qtbot, tmp_path
):
    win = designer
    before = _haptic_emphasis(win, qtbot, tmp_path / "before.haptic")
    envelopes = win.doc.project.tracks[0].clips[0].id
    start = clip_point(win, envelopes, 0.1)  # left of the first emphasis (0.3 s) in time
    drag(win, start, start + QPoint(round(0.1 * PX), 0))  # 20 px: 100 ms later
    if os.environ.get("HT_SCREENSHOTS"):
        win.grab().save(str(Path(os.environ["HT_SCREENSHOTS"]) / "design_moved.png"))
    designs, accents = _starts(win)
    assert designs[0] == pytest.approx(0.1, abs=0.5 / PX)
    assert accents == pytest.approx([0.3 + designs[0], 0.7 + designs[0]], abs=1e-12)
    after = _haptic_emphasis(win, qtbot, tmp_path / "after.haptic")
    assert [a[0] - b[0] for a, b in zip(after, before, strict=True)] == pytest.approx(
        [0.1, 0.1], abs=0.5 / PX
    )
    assert [a[1:] for a in after] == [b[1:] for b in before]
    QTest.keyClick(win, Qt.Key.Key_Z, Qt.KeyboardModifier.ControlModifier)
    assert _starts(win) == ([0.0], [0.3, 0.7])
    # an emphasis dragged on its own still moves alone
    first = win.doc.project.tracks[1].clips[0].id
    press = clip_point(win, first) + QPoint(3, 0)
    drag(win, press, press + QPoint(round(0.1 * PX), 0))
    assert _starts(win)[0] == [0.0] and _starts(win)[1][1] == 0.7


def test_delete_duplicate_copy_and_nudge_of_the_design_clip_include_its_emphasis(designer, qtbot):
    win = designer
    envelopes = win.doc.project.tracks[0].clips[0].id
    accents = [c.id for c in win.doc.project.tracks[1].clips]
    click(win, clip_point(win, envelopes, 0.1))
    # drawn selected with the design (they travel with it) while the selection is the design
    assert win.doc.selected_clips == [envelopes]
    assert all(win.view.clip_item(c).selected for c in [envelopes, *accents])
    click(win, clip_point(win, accents[0]) + QPoint(3, 0))
    assert [c for c in [envelopes, *accents] if win.view.clip_item(c).selected] == accents[:1]
    click(win, clip_point(win, envelopes, 0.1))
    if os.environ.get("HT_SCREENSHOTS"):
        win.grab().save(str(Path(os.environ["HT_SCREENSHOTS"]) / "design_selected.png"))
    QTest.keyClick(win.view.viewport(), Qt.Key.Key_Delete)
    assert _starts(win) == ([], [])
    QTest.keyClick(win, Qt.Key.Key_Z, Qt.KeyboardModifier.ControlModifier)
    assert _starts(win) == ([0.0], [0.3, 0.7])
    click(win, clip_point(win, envelopes, 0.1))
    QTest.keyClick(win, Qt.Key.Key_D, Qt.KeyboardModifier.ControlModifier)  # into the gap after
    designs, accents = _starts(win)
    assert designs == [0.0, 1.2] and accents == pytest.approx([0.3, 0.7, 1.5, 1.9])
    assert len(win.doc.selected_clips) == 3  # the copy and its emphasis, ready to move on
    QTest.keyClick(win, Qt.Key.Key_Z, Qt.KeyboardModifier.ControlModifier)
    click(win, clip_point(win, envelopes, 0.1))
    QTest.keyClick(win, Qt.Key.Key_Right, Qt.KeyboardModifier.AltModifier)  # one grid step
    step = win.view.scene().grid_step()
    assert _starts(win) == ([step], pytest.approx([0.3 + step, 0.7 + step]))
    QTest.keyClick(win, Qt.Key.Key_Z, Qt.KeyboardModifier.ControlModifier)
    click(win, clip_point(win, envelopes, 0.1))
    QTest.keyClick(win, Qt.Key.Key_C, Qt.KeyboardModifier.ControlModifier)
    win.view.scene().set_cursor(2.0)
    QTest.keyClick(win, Qt.Key.Key_V, Qt.KeyboardModifier.ControlModifier)
    designs, accents = _starts(win)
    assert designs == [0.0, 2.0] and accents == pytest.approx([0.3, 0.7, 2.3, 2.7])
    pasted = win.doc.project.tracks[0].clips[1].id
    assert win.doc.project.tracks[1].clips[2].id in vibration.emphasis_of(win.doc.project, pasted)


def test_a_frequency_drag_while_playing_reaches_the_device(designer, qtbot):
    win = designer
    click(win, clip_point(win, win.doc.project.tracks[0].clips[0].id, 0.1))
    editor, canvas = win.editor, win.editor.canvas
    choose(qtbot, editor.lane_box, "Frequency")
    win.activateWindow()
    qtbot.waitUntil(win.isActiveWindow, timeout=5_000)
    win.transport.loop.setChecked(True)
    QTest.keyClick(win, Qt.Key.Key_Space)
    assert win.player.playing
    stream = win.player.stream
    qtbot.waitUntil(lambda: stream.state.live_version >= 0, timeout=5_000)
    before = stream.state.version
    press = QPoint(int(canvas.x_of(0.6)), int(canvas.y_of(0.3)))
    _drag_on(canvas, press, QPoint(press.x(), int(canvas.y_of(0.6))))
    assert stream.state.version > before  # each step of the drag handed to the stream
    played = stream._project.tile(editor.tile_id).design.frequency[1]
    assert played == editor.tile.design.frequency[1] and played[1] == pytest.approx(0.6, abs=0.02)
    qtbot.waitUntil(lambda: stream.state.live_version == stream.state.version, timeout=5_000)
    QTest.keyClick(win, Qt.Key.Key_Space)
    assert not win.player.playing
