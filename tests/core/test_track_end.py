"""A track's end, carried from the track an edit came from, is the latest end of its clips."""

import contextlib
from dataclasses import replace

from hypothesis import given, settings
from hypothesis import strategies as st

from timeline import edits
from timeline.edits.history import History
from timeline.errors import EditError
from timeline.tiles import generator

STEPS = st.lists(
    st.tuples(
        st.sampled_from(["move", "move_track", "add", "remove", "shift", "split", "trim", "undo"]),
        st.integers(0, 50),
        st.floats(min_value=0.0, max_value=4.0, allow_nan=False),
    ),
    max_size=25,
)


def _start():
    project = edits.new_project(templates=False)
    project, tile = edits.add_tile(project, generator("sine", 0.7, frequency=5))
    for _ in range(2):
        project, track = edits.add_track(project, "drive")
        for start in (0.0, 0.5, 1.25):
            project, _ = edits.add_clip(project, track, tile, start)
    return project, tile


def _step(project, tile, op: str, k: int, value: float):
    clips = [c for t in project.tracks for c in t.clips]
    chosen = clips[k % len(clips)] if clips else None
    track_id = project.tracks[k % len(project.tracks)].id
    if op == "add" or chosen is None:
        return edits.add_clip(project, track_id, tile, value)[0]
    if op == "move":
        return edits.move_clip(project, chosen.id, value)
    if op == "move_track":
        return edits.move_clip(project, chosen.id, value, track_id)
    if op == "remove":
        return edits.remove_clips(project, [chosen.id, clips[(k * 7) % len(clips)].id])
    if op == "shift":
        return edits.shift_clips(project, [c.id for c in clips[k % 3 :: 2]], value - 2.0)
    if op == "split":
        return edits.split_clip(project, chosen.id, chosen.start + 0.3)[0]
    return edits.trim_clip(project, chosen.id, end=chosen.start + 0.1 + value / 10)


@settings(max_examples=60, deadline=None)
@given(STEPS)
def test_a_tracks_end_after_any_edits_and_undo_is_the_latest_end_of_its_clips(steps):
    project, tile = _start()
    history = History(project)
    for op, k, value in steps:
        if op == "undo":
            project = history.undo()
        else:
            with contextlib.suppress(EditError):
                project = history.do(op, _step(project, tile, op, k, value))
        for track in project.tracks:  # known now, so the next edit carries them over
            assert track.end == max((c.end for c in track.clips), default=0.0)
        assert project.duration == max((c.end for t in project.tracks for c in t.clips), default=0)


def test_a_moved_clip_carries_its_tracks_ends_and_a_stranger_is_not_taken_for_one():
    project, _ = _start()
    track = project.tracks[0]
    assert track.end == 1.25 + 0.7
    moved = edits.move_clip(project, track.clips[-1].id, 0.1).tracks[0]
    assert "_ends" in moved.__dict__  # carried, not walked
    assert moved.end == 0.5 + 0.7
    stranger = replace(track.clips[-1], start=3.0)  # no clip of the track ends at 3.7
    kept = track.with_clips(track.clips[:2], gone=[stranger])
    assert "_ends" not in kept.__dict__
    assert kept.end == 0.5 + 0.7
