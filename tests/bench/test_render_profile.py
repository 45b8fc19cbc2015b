"""The render profile's floor counts exactly the sin/cos evaluations a render's numpy forms make."""

from __future__ import annotations

from timeline import edits
from timeline.bench.render_profile import libm_seconds
from timeline.tiles import generator


def _project():
    project = edits.new_project(templates=False)
    project, track = edits.add_track(project, "drive")
    project, sine = edits.add_tile(project, generator("sine", 1.0, frequency=40.0))
    project, am = edits.add_tile(project, generator("am", 0.5))
    project, _ = edits.add_clip(project, track, sine, 0.0)
    project, _ = edits.add_clip(project, track, am, 2.0)
    return project


def test_the_libm_floor_counts_one_sin_a_sine_sample_and_two_an_am_sample():
    project = _project()
    assert project.rate == 10_000.0
    _seconds, calls = libm_seconds(project, 3.0)  # the time is the bench's to report
    assert calls == 10_000 + 2 * 5_000
