"""Huge terms that cancel: the small clip under them survives (timeline/rendering/exact_sum.py)."""

from __future__ import annotations

import math

from timeline import edits
from timeline.model import Project
from timeline.rendering.mixer import Mixer
from timeline.tiles import generator


def cancelling(gains: list[float], at: float = 0.0) -> Project:
    """Clips of one 25 Hz sine on a drive track (full scale 0.18), in this order, from `at`."""
    project = edits.new_project(templates=False)
    project, track = edits.add_track(project, "drive")
    project, tile = edits.add_tile(project, generator("sine", 0.01, frequency=25.0))
    for gain in gains:
        project, _ = edits.add_clip(project, track, tile, at, gain=gain)
    return project


EXACT = 0.18 * 0.5 * math.sin(2 * math.pi * 25 * 10 / 10_000)  # the 0.5 clip at its sample 10


def test_a_half_gain_clip_under_two_of_1e15_that_cancel_renders_as_itself() -> None:
    out = Mixer().render(cancelling([0.5, 1e15, -1e15]), 0.0, 0.01, 10_000.0)["drive"]
    assert abs(out[10] - EXACT) <= 1e-15  # a plain float64 sum gave 0.015625
    assert out[0] == 0.0


def test_an_edit_re_sums_only_its_block_and_keeps_the_small_clip() -> None:
    """4 s at 10 kHz is two blocks; the edit at 3.5 s sums the second again on its own."""
    mixer = Mixer()
    project = cancelling([0.5, 1e15, -1e15, 1.0], at=3.5)
    mixer.render(project, 0.0, 4.0, 10_000.0)
    last = project.tracks[0].clips[-1]
    sums = mixer.stats.block_sums
    out = mixer.render(edits.set_clip(project, last.id, gain=0.0), 0.0, 4.0, 10_000.0)["drive"]
    assert mixer.stats.block_sums == sums + 1
    assert abs(out[35_010] - EXACT) <= 1e-15
