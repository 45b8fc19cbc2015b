"""The fan knob felt inside the editor: the hand box applies, the playhead follows the angle."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from PySide6.QtCore import Qt
from PySide6.QtTest import QTest
from PySide6.QtWidgets import QMessageBox

from timeline.plugins.device_protocol import HAND_MODELS, HAND_MODES, Hand
from timeline.rendering import playback

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture
def fan_knob(qtbot):
    """The editor with projects/fan_knob.htl opened the way a person opens it."""
    from timeline.gui.main_window import MainWindow

    win = MainWindow()
    win.ask_unsaved = lambda: QMessageBox.StandardButton.Discard
    qtbot.addWidget(win)
    win.show()
    qtbot.waitExposed(win)
    assert win.open_path(ROOT / "projects" / "fan_knob.htl")
    yield win
    win.player.close()


def choose_hand(win, mode: str, value: str | None = None) -> None:
    """Pick the hand with the arrow keys in its box, then type its speed or torque."""
    combo = win.transport.hand
    QTest.mouseClick(combo, Qt.MouseButton.LeftButton)
    combo.hidePopup()
    QTest.keyClick(combo, Qt.Key.Key_Home)
    for _ in range(HAND_MODES.index(mode)):
        QTest.keyClick(combo, Qt.Key.Key_Down)
    if value is not None:
        box = win.transport.hand_value
        QTest.keyClick(box, Qt.Key.Key_A, Qt.KeyboardModifier.ControlModifier)
        QTest.keyClicks(box, value)
        QTest.keyClick(box, Qt.Key.Key_Return)


def choose_model(win, name: str) -> None:
    """Pick whose hand with a click on its box and the arrow keys."""
    combo = win.transport.hand_model
    QTest.mouseClick(combo, Qt.MouseButton.LeftButton)
    combo.hidePopup()
    QTest.keyClick(combo, Qt.Key.Key_Home)
    for _ in range(list(HAND_MODELS).index(name)):
        QTest.keyClick(combo, Qt.Key.Key_Down)


def record(win) -> list[tuple[np.ndarray, np.ndarray]]:
    parts: list[tuple[np.ndarray, np.ndarray]] = []
    win.player.telemetry.connect(lambda a, t: parts.append((a.copy(), t.copy())))
    return parts


def test_fan_knob_turned_sweeps_the_table_and_each_detent_pushes_back(fan_knob, qtbot):
    win = fan_knob
    choose_hand(win, "turn", "180")
    assert str(win.player.hand) == "turn:180"
    parts = record(win)
    with qtbot.waitSignal(win.player.finished, timeout=30_000) as done:
        QTest.mouseClick(win.transport.play_button, Qt.MouseButton.LeftButton)
        assert win.player.playing
        assert win.transport.play_button.text() == "■ Stop"
    assert done.args == [""]
    angle = np.degrees(np.concatenate([a for a, _ in parts]))
    torque = 1e3 * np.concatenate([t for _, t in parts])  # mNm
    table, _ = playback.position_table(win.doc.project)
    rests = np.degrees(playback.rest_angles(table))
    assert rests == pytest.approx([50.0, 110.0, 170.0, 230.0], abs=0.1)
    # the knob starts on the first detent (Off) and the hand turns it through Lo, Med, Hi
    assert angle[0] == pytest.approx(50.0, abs=0.5)
    assert angle.max() > 260.0  # into the wall beyond Hi
    for rest in rests[1:]:
        before = torque[(angle > rest - 20) & (angle < rest - 3)]
        after = torque[(angle > rest + 3) & (angle < rest + 20)]
        assert before.size > 50 and after.size > 50
        assert np.all(before > 0) and np.all(after < 0)  # the detent pulls the knob into it
        assert before.mean() > 20.0 and after.mean() < -20.0
    # the playhead stopped where the knob did, on the degrees ruler and in the readout
    end = math.degrees(win.view.scene().playhead_u)
    assert end == pytest.approx(angle[-1], abs=0.01)
    assert win.transport.where.text() == f"{end:.1f}°"
    assert win.transport.scope.theta[-1] == pytest.approx(angle[-1], abs=2.0)
    assert win.transport.play_button.text() == "▶ Play"


def test_holding_hand_plays_until_stop_and_a_new_hand_applies_at_once(fan_knob, qtbot):
    win = fan_knob
    choose_hand(win, "hold")
    assert win.player.hand.mode == "hold"
    QTest.keyClick(win, Qt.Key.Key_Space)
    assert win.player.playing
    qtbot.waitUntil(lambda: win.transport.scope.theta.size > 20, timeout=15_000)
    held = math.degrees(win.view.scene().playhead_u)
    assert held == pytest.approx(50.0, abs=0.5)  # held still on Off
    choose_hand(win, "push", "100")  # push harder than a detent (about 29 mNm) holds
    assert str(win.player.hand) == "push:100"
    assert win.player.playing
    qtbot.waitUntil(lambda: math.degrees(win.view.scene().playhead_u) > 250.0, timeout=15_000)
    # 100 mNm flings the knob past the wall's end (0.8 x 180 mNm at 280 deg); wait until it has
    # come back and rests where the wall balances the push (1 ms per scope sample)
    qtbot.waitUntil(lambda: np.ptp(win.transport.scope.theta[-100:]) < 0.2, timeout=15_000)
    assert math.degrees(win.view.scene().playhead_u) == pytest.approx(273.9, abs=1.0)
    assert win.transport.scope.tau[-1] < 0  # the wall beyond Hi pushes back
    # zoomed in, the view pages along so the playhead stays on screen
    win.view.zoom(4.0)
    win.view.horizontalScrollBar().setValue(0)
    assert win.view.lane_geometry.x(win.view.scene().playhead_u) > win.view.viewport().width()
    qtbot.waitUntil(lambda: win.view.horizontalScrollBar().value() > 0, timeout=15_000)
    x = (
        win.view.lane_geometry.x(win.view.scene().playhead_u)
        - win.view.horizontalScrollBar().value()
    )
    assert 0 <= x <= win.view.viewport().width()
    QTest.mouseClick(win.transport.play_button, Qt.MouseButton.LeftButton)
    assert not win.player.playing
    assert win.transport.play_button.text() == "▶ Play"


def test_a_new_hand_in_a_time_project_carries_on_from_where_it_played(window, qtbot):
    win = window
    QTest.mouseClick(win.transport.play_button, Qt.MouseButton.LeftButton)  # from the cursor, 0
    assert win.player.playing
    qtbot.waitUntil(lambda: win.view.scene().playhead_u > 0.3, timeout=15_000)
    choose_hand(win, "turn", "45")
    assert str(win.player.hand) == "turn:45" and win.player.playing
    qtbot.waitUntil(lambda: win.player.stream.state.position > 0.0, timeout=15_000)
    assert win.player.stream.start > 0.3  # restarted where it was, not from the cursor at 0
    QTest.mouseClick(win.transport.play_button, Qt.MouseButton.LeftButton)
    assert not win.player.playing


def test_a_measured_hand_chosen_in_the_box_holds_the_knob_with_its_grip(fan_knob, qtbot):
    """Whose hand is its own box: its grip (grasp 0.054, pinch 0.129 N*m/rad) goes with any
    mode, the tooltip names the source, and the played telemetry comes from that hand."""
    win = fan_knob
    choose_model(win, "grasp")
    assert win.player.hand == Hand("hold", model="grasp") and str(win.player.hand) == "grasp"
    tip = win.transport.hand_model.itemData(2, Qt.ItemDataRole.ToolTipRole)
    assert "van Beek" in tip and "Fig. 3f" in tip
    choose_hand(win, "turn", "45")
    assert str(win.player.hand) == "grasp-turn:45"
    assert win.player.hand.grip_stiffness == pytest.approx(0.054)
    choose_model(win, "pinch")
    assert str(win.player.hand) == "pinch-turn:45"
    assert win.player.hand.grip_stiffness == pytest.approx(0.129375)
    parts = record(win)
    QTest.keyClick(win, Qt.Key.Key_Space)
    qtbot.waitUntil(lambda: sum(a.size for a, _ in parts) > 2000, timeout=15_000)
    QTest.keyClick(win, Qt.Key.Key_Space)
    angle = np.degrees(np.concatenate([a for a, _ in parts]))
    assert angle[0] == pytest.approx(50.0, abs=0.5) and angle[-1] > angle[0]  # turning from Off
    choose_model(win, "default")
    assert str(win.player.hand) == "turn:45" and win.player.hand.grip_stiffness == 1.0
