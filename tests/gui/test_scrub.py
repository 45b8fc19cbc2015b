"""Scrub: dragging the playhead on the ruler plays what is under it on the device (grains of
the mix in a time project, the knob held at the angle in a position project), nothing after."""

from __future__ import annotations

import math

import numpy as np
import pytest
from PySide6.QtCore import QPoint, Qt
from PySide6.QtTest import QTest

from timeline import render
from timeline.gui.scrub import GRAIN_SECONDS

from .helpers import shown_window
from .test_exact_values import rough_fan_knob

LEFT = Qt.MouseButton.LeftButton


@pytest.fixture
def knob(qtbot):
    """The main window on a fan knob (detents over 240 degrees), fitted to the lanes."""
    project, _, _ = rough_fan_knob()
    win = shown_window(qtbot, project)
    win.view.fit()
    yield win
    win.player.close()
    win.autosaver.discard()


class Recorder:
    """What the player reports: telemetry torque (N*m) and angle (rad) since the last take."""

    def __init__(self, player) -> None:
        self.angle: list[np.ndarray] = []
        self.torque: list[np.ndarray] = []
        player.telemetry.connect(self._add)

    def _add(self, angle, torque) -> None:
        self.angle.append(np.array(angle))
        self.torque.append(np.array(torque))

    def take(self) -> tuple[np.ndarray, np.ndarray]:
        angle = np.concatenate(self.angle) if self.angle else np.zeros(0)
        torque = np.concatenate(self.torque) if self.torque else np.zeros(0)
        self.angle, self.torque = [], []
        return angle, torque


def settle(qtbot, win) -> None:
    """Wait until the grain has played and the player has said so."""
    qtbot.waitUntil(lambda: not win.player.playing, timeout=15_000)
    qtbot.wait(120)  # the player's timer passes the last telemetry on


def test_scrubbing_a_time_project_plays_grains_of_the_mix_at_the_playhead(window, qtbot):
    win = window
    ruler = win.ruler
    rate = win.player._open().info.rate
    heard = Recorder(win.player)
    start = QPoint(round(ruler.x_of(0.0)), 30)  # on the playhead
    QTest.mousePress(ruler, LEFT, pos=start)
    played = []
    for x in (ruler.x_of(0.6), ruler.x_of(0.9), ruler.x_of(1.3), ruler.x_of(2.2)):
        QTest.mouseMove(ruler, QPoint(round(x), 30))
        u = win.view.scene().playhead_u
        assert u == pytest.approx(ruler.u_of(round(x)))
        stream = win.player.stream  # a grain from the playhead
        assert stream is not None and (stream.start, stream.stop) == (u, u + GRAIN_SECONDS)
        settle(qtbot, win)  # the mouse rests: the grain ends by itself
        _, torque = heard.take()
        played.append((u, torque))
    assert win.ruler.scrubber.active
    QTest.mouseRelease(ruler, LEFT, pos=QPoint(round(ruler.x_of(2.2)), 30))
    assert not win.player.playing
    project = win.doc.project
    for u, torque in played:
        expected = render(project, u, u + GRAIN_SECONDS, rate)
        mix = sum(expected.values())
        assert len(torque) == len(mix) == round(GRAIN_SECONDS * rate)
        np.testing.assert_allclose(torque, mix, rtol=0, atol=1e-12)
        assert np.abs(mix).max() > 1e-3  # each grain is under a clip: there is something to feel
    # after the release nothing plays, and the playhead stays where it was let go
    qtbot.wait(300)
    assert not win.player.playing and heard.take()[1].size == 0
    assert win.view.scene().playhead_u == pytest.approx(ruler.u_of(round(ruler.x_of(2.2))))
    assert win.transport.play_button.text() == "▶ Play"


def test_a_scrub_let_go_while_playing_plays_on_from_there(window, qtbot):
    win = window
    ruler = win.ruler
    QTest.keyClick(win, Qt.Key.Key_Space)
    assert win.player.playing
    start = QPoint(round(ruler.x_of(win.view.scene().playhead_u)), 30)
    end = QPoint(round(ruler.x_of(1.25)), 30)
    QTest.mousePress(ruler, LEFT, pos=start)
    QTest.mouseMove(ruler, (start + end) / 2)
    assert win.player.stream is not None and win.player.stream.stop < 1.0  # a grain
    QTest.mouseMove(ruler, end)
    QTest.mouseRelease(ruler, LEFT, pos=end)
    stream = win.player.stream
    assert win.player.playing and stream is not None
    assert stream.start == pytest.approx(ruler.u_of(end.x()))
    assert stream.stop == win.doc.project.duration
    assert win.transport.play_button.text() == "■ Stop"
    QTest.keyClick(win, Qt.Key.Key_Space)
    assert not win.player.playing


def test_a_scrub_holds_the_knob_at_the_angle_of_a_position_project(knob, qtbot):
    win = knob
    ruler = win.ruler
    win.transport.hand.setCurrentText("turn")  # the chosen hand turns; a scrub holds
    hand = win.player.hand
    assert hand.mode == "turn"
    heard = Recorder(win.player)
    start = QPoint(round(ruler.x_of(win.view.scene().playhead_u)), 30)
    QTest.mousePress(ruler, LEFT, pos=start)
    for deg in (35.0, 80.0, 140.0):
        QTest.mouseMove(ruler, QPoint(round(ruler.x_of(math.radians(deg))), 30))
        u = win.view.scene().playhead_u
        qtbot.waitUntil(lambda: len(heard.torque) >= 4, timeout=15_000)
        heard.take()
        qtbot.waitUntil(lambda: len(heard.torque) >= 2, timeout=15_000)  # held a while
        angle, torque = heard.take()
        assert win.player.playing and win.player.hand.mode == "hold"
        table = render(win.doc.project, 0.0, math.radians(300))
        grid = np.arange(len(next(iter(table.values())))) / win.doc.project.rate
        field = np.interp(angle, grid, sum(table.values()))
        np.testing.assert_allclose(torque, field, rtol=0, atol=1e-9)
        assert np.abs(field).max() > 1e-3  # there is a force to feel at each angle
        # the hand holds the knob at the playhead: it gives way by the field over its grip
        rest = u + torque / win.player.hand.grip_stiffness
        assert np.abs(angle - rest).max() < math.radians(0.1)
    QTest.mouseRelease(ruler, LEFT, pos=QPoint(round(ruler.x_of(math.radians(140))), 30))
    assert not win.player.playing and win.player.hand == hand
    qtbot.wait(300)
    assert not win.player.playing and heard.take()[1].size == 0
