"""A time project plays on the sim from a process of its own: a thread of the editor's process
holding the interpreter lock delays no block, an edit made meanwhile is felt, and a project
crosses to it as the tracks and tiles that changed."""

from __future__ import annotations

import queue
import time

import numpy as np
import pytest

from timeline import edits
from timeline.gui.live_stream import LiveStream
from timeline.gui.play_process import PlayProcess, delta, rebuild
from timeline.plugins.device_protocol import Hand, open_device
from timeline.tiles import generator


def two_tracks():
    project = edits.new_project()
    project, tile = edits.add_tile(project, generator("sine", 3.0, frequency=3))
    project, track = edits.add_track(project, "drive")
    project, clip = edits.add_clip(project, track, tile, 0.0)
    project, other = edits.add_track(project, "drive")
    project, _ = edits.add_clip(project, other, tile, 5.0)
    return project, clip


def test_a_project_crosses_as_the_tracks_and_tiles_that_changed():
    project, clip = two_tracks()
    quieter = edits.set_clip_gain(project, clip, 0.25)
    change = delta(project, quieter)
    assert change.tracks[1] == project.tracks[1].id  # unchanged: its id only
    assert change.tracks[0] is quieter.tracks[0] and change.tiles == {} and change.gone == ()
    rebuilt = rebuild(rebuild(None, delta(None, project)), change)
    assert rebuilt.tracks == quieter.tracks and dict(rebuilt.tiles) == dict(quieter.tiles)
    more, tile = edits.add_tile(quieter, generator("square", 1.0, frequency=5))
    assert list(delta(quieter, more).tiles) == [tile]
    assert dict(rebuild(rebuilt, delta(quieter, more)).tiles) == dict(more.tiles)


@pytest.fixture(scope="module")
def sim_process():
    """One play process on the sim for the tests below (starting one costs seconds)."""
    process = PlayProcess("sim")
    yield process
    process.close()


def test_the_sim_plays_on_time_from_its_process_while_the_editors_lock_is_held(
    busy_interpreter, sim_process
):
    project, clip = two_tracks()
    project = edits.set_clip_gain(project, clip, 0.5)
    quieter = edits.set_clip_gain(project, clip, 0.125)
    process = sim_process
    process.warm(project, 0.0)  # as the editor does once its window has painted
    with busy_interpreter():
        process.send("play", project, 0.0, 1.2, False, None, Hand("hold"), time.perf_counter())
        time.sleep(0.5)
        process.send("edit", quieter, 1)
        messages = process.wait_done(timeout=10.0)
    kind, outcome, counts = messages[-1]
    assert (kind, outcome) == ("done", "")
    assert counts.blocks == 120 and counts.late == 0
    assert any(m[0] == "at" and m[2] == 1 for m in messages)  # the edit went out
    parts = [m[1] for m in messages if m[0] == "part"]
    t = np.concatenate([p.time for p in parts])
    torque = np.concatenate([p.torque for p in parts])
    before, after = np.abs(torque[t < 0.3]).max(), np.abs(torque[t >= 0.9]).max()
    assert after == pytest.approx(before / 4, rel=1e-3)  # gain 0.5, then 0.125


def test_the_usb_knobs_blocks_come_from_the_play_process_while_the_editors_lock_is_held(
    busy_interpreter, monkeypatch
):
    monkeypatch.setenv("HAPTIC_TIMELINE_USB_EMULATE", "realtime")  # the knob on the wall clock
    project, clip = two_tracks()
    project = edits.set_clip_gain(project, clip, 0.5)
    process = PlayProcess("usb")
    try:
        assert process.info.lead > 0.1  # streamed from the stream process the child started
        process.warm(project, 0.0)
        with busy_interpreter():  # the editor's blocks would arrive 25 ms apart at best
            process.send("play", project, 0.0, 0.6, False, None, Hand("hold"), time.perf_counter())
            messages = process.wait_done(timeout=20.0)
    finally:
        process.close()
    kind, outcome, counts = messages[-1]
    assert (kind, outcome) == ("done", "")  # an underrun would have stopped it, and said so
    assert counts.blocks == 60 and counts.late == 0
    torque = np.concatenate([m[1].torque for m in messages if m[0] == "part"])
    assert np.abs(torque).max() == pytest.approx(0.5 * 0.18, rel=0.05)  # half the sine's peak


def test_the_first_play_after_the_hand_over_plays_the_in_process_render_bit_for_bit(sim_process):
    project, _ = two_tracks()
    sim_process.warm(project, 0.0)  # the project crosses, as at start-up; the Play sends ids
    sim_process.send("play", project, 0.0, 0.05, False, None, Hand("hold"), time.perf_counter())
    messages = sim_process.wait_done(timeout=10.0)
    assert messages[-1][:2] == ("done", "")
    played = np.concatenate([m[1].torque for m in messages if m[0] == "part"])
    with open_device("sim") as knob:  # the same knob and blocks, rendered in this process
        stream = LiveStream(project, knob.info.rate, 0.0, 0.05, paced=False)
        expected = knob.play(stream, Hand("hold")).torque
    assert len(played) == 500 and np.abs(expected).max() > 0.01
    np.testing.assert_array_equal(played, expected)


def test_a_stopped_plays_late_messages_are_not_taken_for_the_next_plays():
    process = PlayProcess.__new__(PlayProcess)  # the host's bookkeeping only, no child
    process._from_child = queue.Queue()
    process._plays = 2  # the host stopped waiting for the first play's end
    first = [("at", 0.5, 0, "first"), ("done", "", "first")]
    second = [("at", 0.0, 0, "second"), ("done", "", "second")]
    for number, messages in ((1, first), (2, second)):
        for message in messages:
            process._from_child.put((number, *message))
    assert process.wait_done(1.0) == second
