"""Late blocks are counted while playing and named in the message bar; the stream plays the
newest project state."""

from __future__ import annotations

import re
import time

import numpy as np

from device.sim import SimKnob
from timeline import edits
from timeline.gui.live_stream import LiveStream
from timeline.tiles import generator

LATE = re.compile(
    r"^\d+ blocks? late, worst \d+ ms, \d+ gaps? over 50 ms: the knob may have gone slack$"
)


class StallingKnob(SimKnob):
    """The sim knob whose playing thread is held up 150 ms after its fifth block, as a starved
    thread would be (past the 30 ms lead and the 50 ms watchdog)."""

    def play(self, program, hand=None, progress=None, monitor=None):
        def stalled():
            for i, block in enumerate(program):
                if i == 5:
                    time.sleep(0.15)
                yield block

        return super().play(stalled(), hand, progress, monitor)


def test_late_blocks_are_counted_and_named_in_the_message_bar(window, qtbot):
    win = window
    if win.player._warm is not None:
        win.player._warm.join()
    win.player.device = StallingKnob()
    win.play_stop(0.0)
    qtbot.waitUntil(lambda: not win.player.playing and win.player._outcome is None, timeout=20_000)
    counts = win.player.lateness
    assert counts is not None and counts.late >= 1 and counts.gaps >= 1
    assert counts.worst >= 0.1  # the block after the stall: 150 ms less at most one lead
    named = [text for text, level in win.messages.history if LATE.match(text)]
    assert named and named[-1] == counts.sentence()  # named when the play ended, with all


def test_an_unpaced_stream_plays_the_newest_state_from_the_next_block():
    project = edits.new_project()
    project, tile = edits.add_tile(project, generator("sine", 1.0, frequency=3))
    project, track = edits.add_track(project, "drive")
    project, clip = edits.add_clip(project, track, tile, 0.0)
    stream = LiveStream(project, 1000.0, 0.0, 1.0, paced=False)
    blocks = iter(stream)
    first = next(blocks)
    np.testing.assert_array_equal(first.d, stream.render(project, 0.0, 0.5).d[:10])
    quieter = edits.set_clip_gain(project, clip, 0.25)
    stream.set_project(quieter)
    second = next(blocks)
    np.testing.assert_array_equal(second.d, stream.render(quieter, 0.01, 0.51).d[:10])
    assert np.abs(second.d).max() > 0 and stream.state.live_version == 1
