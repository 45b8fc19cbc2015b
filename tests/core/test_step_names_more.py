"""Undo step names named by the edits mutation run: variants, several clips, a split, a clip
moved to another track, tracks, markers and the loop (a time project: seconds)."""

from __future__ import annotations

import numpy as np

from timeline import edits
from timeline.edits import markers
from timeline.edits.step_names import step_name
from timeline.model import Project
from timeline.tiles import SampledTile

RATE = 1000.0


def _project() -> tuple[Project, str, str]:
    project = edits.new_project("time", rate=RATE, templates=False)
    project, track = edits.add_track(project, "drive")
    project, tile = edits.add_tile(project, SampledTile(np.ones(10), RATE, "ramp"))
    project, clip = edits.add_clip(project, track, tile, 0.0)  # 0 to 0.01 s
    return project, track, clip


def test_deleting_two_variants_names_both() -> None:
    project = edits.save_variant(edits.save_variant(_project()[0], "A"), "B")
    gone = edits.remove_variant(edits.remove_variant(project, "A"), "B")
    assert step_name("delete variants", project, gone) == "delete variant A, B"


def test_clips_moved_together_say_by_how_much() -> None:
    project, track, clip = _project()
    project, other = edits.add_clip(project, track, project.find_clip(clip)[1].tile_id, 0.02)
    shifted = edits.shift_clips(project, [clip, other], 0.5)
    assert step_name("drag them", project, shifted) == "move 2 clips by +0.5 s"


def test_a_split_says_where() -> None:
    project, _, clip = _project()
    split, _ = edits.split_clip(project, clip, 0.005)
    assert step_name("split", project, split) == "split 'ramp' at 0.005 s"


def test_a_clip_moved_to_another_track_says_which_and_where() -> None:
    project, _, clip = _project()
    project, other = edits.add_track(project, "drive")
    moved = edits.move_clip(project, clip, 0.002, other)
    assert step_name("move clip", project, moved) == "move 'ramp' to 'Drive 2' at 0.002 s"


def test_a_trim_from_the_start_says_the_new_span() -> None:
    project, _, clip = _project()
    trimmed = edits.trim_clip(project, clip, start=0.002)
    assert step_name("trim", project, trimmed) == "trim 'ramp' to 0.002 s–0.01 s"


def test_one_added_track_is_named() -> None:
    project = _project()[0]
    added, _ = edits.add_track(project, "drive")
    assert step_name("add track", project, added) == "add track 'Drive 2'"


def test_markers_and_the_loop_are_named() -> None:
    project = _project()[0]
    looped = markers.set_loop(project, 0.1, 0.2)
    assert step_name("loop", project, looped) == "loop 0.1 s–0.2 s"
    project, _ = markers.add_marker(project, 0.3, "B")
    project, index = markers.add_marker(project, 0.1, "A")
    gone = markers.remove_marker(project, index)
    assert step_name("delete marker", project, gone) == "delete marker 'A'"
    renamed = markers.rename_marker(project, index, "C")
    assert step_name("rename marker", project, renamed) == "rename marker 'A' to 'C'"
