"""A time project plays on the sim from a process of its own: a thread of the editor's process
holding the interpreter lock delays no block, an edit made meanwhile is felt, and a project
crosses to it as the tracks and tiles that changed."""

from __future__ import annotations

import time

import numpy as np
import pytest

from timeline import edits
from timeline.gui.play_process import PlayProcess, delta, rebuild
from timeline.plugins.device_protocol import Hand
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


def test_the_sim_plays_on_time_from_its_process_while_the_editors_lock_is_held(busy_interpreter):
    project, clip = two_tracks()
    project = edits.set_clip_gain(project, clip, 0.5)
    quieter = edits.set_clip_gain(project, clip, 0.125)
    process = PlayProcess("sim")
    try:
        process.warm(project, 0.0)  # as the editor does once its window has painted
        with busy_interpreter():
            process.send("play", project, 0.0, 1.2, False, None, Hand("hold"), time.perf_counter())
            time.sleep(0.5)
            process.send("edit", quieter, 1)
            messages = process.wait_done(timeout=10.0)
    finally:
        process.close()
    kind, outcome, counts = messages[-1]
    assert (kind, outcome) == ("done", "")
    assert counts.blocks == 120 and counts.late == 0
    assert any(m[0] == "at" and m[2] == 1 for m in messages)  # the edit went out
    parts = [m[1] for m in messages if m[0] == "part"]
    t = np.concatenate([p.time for p in parts])
    torque = np.concatenate([p.torque for p in parts])
    before, after = np.abs(torque[t < 0.3]).max(), np.abs(torque[t >= 0.9]).max()
    assert after == pytest.approx(before / 4, rel=1e-3)  # gain 0.5, then 0.125
