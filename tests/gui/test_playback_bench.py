"""The playback benchmark's row counts the blocks of the play it asked for, however long the
GUI thread stalls while it plays."""

from __future__ import annotations

import time

from timeline.bench import playback_session


def test_a_stalled_gui_thread_does_not_lengthen_the_benchmarks_play(window, qapp, monkeypatch):
    win = window
    if win.player._warm is not None:
        win.player._warm.join()
    stall = (lambda: time.sleep(0.25), lambda: None)  # each frame holds the GUI thread 250 ms
    monkeypatch.setattr(playback_session, "_gesture", lambda _win, _gesture: stall)
    row = playback_session._play(qapp, win, "stall", 0.3)
    assert row["ended"] == ""
    assert row["blocks"] == 30  # 0.3 s of 10 ms blocks, not the 0.5 s the stalls lasted
