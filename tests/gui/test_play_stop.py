"""Stopping a play in the play process does not wait for it on the GUI thread: the USB knob's
play ends after the Stop returned (its queue played out, then STOP, the ramp to zero), the
player hears that end, and the process ends cleanly."""

from __future__ import annotations

from timeline import edits
from timeline.gui.player import Player, _Shared
from timeline.tiles import generator


def test_a_usb_stop_returns_before_the_play_has_ended(qtbot, monkeypatch):
    monkeypatch.setenv("HAPTIC_TIMELINE_USB_EMULATE", "realtime")  # the knob on the wall clock
    project = edits.new_project()
    project, tile = edits.add_tile(project, generator("sine", 3.0, frequency=3))
    project, track = edits.add_track(project, "drive")
    project, _ = edits.add_clip(project, track, tile, 0.0)
    player = Player()
    player.choose_device("usb")
    ended: list[str] = []
    player.finished.connect(ended.append)
    try:
        for _ in range(2):
            player.play(project, 0.0, 3.0)
            qtbot.waitUntil(lambda: _heard(player) >= 5, timeout=30_000)
            player.stop()
            assert not player.playing and ended == []
        process = _Shared.process
        # the second play's end was still to come when stop returned: the child says it now
        done = process.wait_done(10.0)[-1]
        assert done[:2] == ("done", "") and 5 <= done[2].blocks < 300
        player.play(project, 0.0, 3.0)  # and the player hears a stopped play's end itself
        qtbot.waitUntil(lambda: _heard(player) >= 5, timeout=30_000)
        player.stop()
        qtbot.waitUntil(lambda: bool(ended), timeout=10_000)
        assert ended == [""] and _heard(player) >= 5
    finally:
        player.close()
        _Shared.close()
    assert process.process.exitcode == 0  # asked to go, it went: not terminated


def _heard(player: Player) -> int:
    """Blocks the play process said it handed over in the current play."""
    counts = player.lateness
    return 0 if counts is None else counts.blocks
