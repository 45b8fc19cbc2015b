"""A project opened later in the window crosses to the play process in the background: the next
Play sends only a delta and plays the new project; the process ends when the application quits."""

from __future__ import annotations

import threading

import numpy as np
import pytest
from PySide6.QtWidgets import QApplication

from timeline import edits
from timeline.files import projectfile
from timeline.gui import player as player_module
from timeline.gui.live_stream import LiveStream
from timeline.gui.play_process import PlayProcess, delta
from timeline.tiles import generator


def quiet_sine():
    """One drive track: a 0.4 s, 5 Hz sine at a quarter gain (the window's own plays at 1)."""
    project = edits.new_project()
    project, tile = edits.add_tile(project, generator("sine", 0.4, frequency=5))
    project, track = edits.add_track(project, "drive")
    project, clip = edits.add_clip(project, track, tile, 0.0)
    return edits.set_clip_gain(project, clip, 0.25)


def saved(project, folder):
    path = folder / "second.htl"
    projectfile.save(project, path)
    return path


def quiet_peak(win) -> float:
    """The peak of the window's project as rendered at the device's rate."""
    project, rate = win.doc.project, win.player.device.info.rate
    peak = np.abs(LiveStream(project, rate, 0.0, 0.4).render(project, 0.0, 0.4).d).max()
    assert peak == pytest.approx(0.25 * 0.18, rel=1e-2)  # a quarter of the sine's 0.18 N*m
    return peak


def peak(torque: list) -> float:
    return np.abs(np.concatenate(torque)).max()


def test_a_play_during_the_hand_over_plays_in_the_editors_process(
    window, qtbot, tmp_path, monkeypatch
):
    win, player = window, window.player
    crossing = threading.Event()
    monkeypatch.setattr(PlayProcess, "warm", lambda *args: crossing.wait(20.0))  # still crossing
    try:
        assert win.open_path(saved(quiet_sine(), tmp_path))
        torque = []
        player.telemetry.connect(lambda _angle, t: torque.append(t))
        win.play_stop(0.0)
        assert player._remote is None and player._thread is not None  # here, not in the child
        qtbot.waitUntil(lambda: not player.playing, timeout=20_000)
    finally:
        crossing.set()
    assert peak(torque) == pytest.approx(quiet_peak(win), rel=1e-3)


def test_an_opened_project_plays_from_a_delta_and_the_process_ends_at_quit(
    window, qtbot, tmp_path, monkeypatch
):
    win, player = window, window.player
    qtbot.waitUntil(lambda: not player._warm_running, timeout=60_000)  # the start-up warm-up
    assert win.open_path(saved(quiet_sine(), tmp_path))
    qtbot.waitUntil(lambda: player._handed.is_set(), timeout=60_000)  # crossed in the background
    sent = []
    send = PlayProcess.send

    def spy(self, kind, project, *args):
        sent.append((kind, delta(self._sent, project)))
        send(self, kind, project, *args)

    monkeypatch.setattr(PlayProcess, "send", spy)
    torque = []
    player.telemetry.connect(lambda _angle, t: torque.append(t))
    win.play_stop(0.0)
    assert player._remote is not None  # played by the child
    qtbot.waitUntil(lambda: not player.playing, timeout=20_000)
    kind, change = sent[0]
    assert kind == "play" and change.tiles == {} and change.gone == ()
    assert change.tracks == tuple(t.id for t in win.doc.project.tracks)  # ids only: no track
    assert peak(torque) == pytest.approx(quiet_peak(win), rel=1e-3)
    process = player_module._Shared.process
    assert process is not None
    win.close()
    QApplication.instance().aboutToQuit.emit()  # the application quits with its last window
    assert process.process.is_alive() is False
    assert player_module._Shared.process is None


def test_a_recovered_autosave_crosses_to_the_play_process_before_any_play(window, qtbot):
    win, player = window, window.player
    recovered = quiet_sine()

    class Entry:  # what autosave.recoverable() finds, as far as `recover` reads it
        original = None

        def load(self):
            return recovered

        def discard(self) -> None:
            pass

    win.recover(Entry())
    qtbot.waitUntil(lambda: player._handed.is_set() and not player._warm_running, timeout=60_000)
    held = player_module._Shared.process._sent  # what the child holds
    assert held.tracks == recovered.tracks and dict(held.tiles) == dict(recovered.tiles)
