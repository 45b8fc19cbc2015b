"""Undo steps are named by what they changed, in the project's display units."""

from __future__ import annotations

import math

from timeline import edits
from timeline.edits import markers
from timeline.edits.history import History
from timeline.edits.step_names import step_name
from timeline.tiles import generator

DEG = math.radians(1.0)


def fan_knob():
    """A position project: one torque track with a detents clip named 'detents copy' at 0°."""
    p = edits.new_project("position")
    p, tile = edits.add_tile(p, generator("detents", 4 * math.pi / 3, "detents copy"), "Scratch")
    p, track = edits.add_track(p, "torque")
    p, clip = edits.add_clip(p, track, tile, 0.0)
    return p, track, clip


def test_a_clip_edit_is_named_in_degrees_and_decibels():
    p, track, clip = fan_knob()
    moved = edits.move_clip(p, clip, 20 * DEG)
    assert step_name("move clip", p, moved) == "move 'detents copy' to 20°"
    quiet = edits.set_clip_gain(p, clip, 0.2)
    assert step_name("gain", p, quiet) == "gain of 'detents copy' to x0.2 (-14.0 dB)"
    faded = edits.set_fade(p, clip, "in", 10 * DEG, "s-curve")
    assert step_name("fade", p, faded) == "fade in of 'detents copy' to 10°"
    trimmed = edits.trim_clip(p, clip, end=200 * DEG)
    assert step_name("trim", p, trimmed) == "trim 'detents copy' to 0°–200°"
    stretched = edits.stretch_clip(p, clip, 1.5)
    assert step_name("stretch", p, stretched) == "stretch 'detents copy' to x1.5 (360°)"
    mirrored = edits.set_pivot(p, clip, 0.25)
    assert step_name("place mirror line", p, mirrored) == (
        "mirror line of 'detents copy' at 0.25 of full scale"
    )
    assert step_name("invert", p, edits.invert_clip(p, clip)) == "invert 'detents copy'"
    gone = edits.remove_clips(p, [clip])
    assert step_name("delete", p, gone) == "delete 'detents copy'"
    assert step_name("cut", p, gone) == "cut 'detents copy'"


def test_an_added_clip_says_where_and_a_time_project_speaks_seconds():
    p = edits.new_project("time")
    p, tile = edits.add_tile(p, generator("sine", 1.0, frequency=5), "Scratch")
    p, track = edits.add_track(p, "drive")
    added, clip = edits.add_clip(p, track, tile, 0.25)
    assert step_name("add clip", p, added) == "add 'sine' at 0.25 s on 'Drive 1'"
    assert step_name("import tap.wav", p, added) == "import tap.wav"  # a label that says more
    both, other = edits.add_clip(added, track, tile, 2.0)
    shifted = edits.shift_clips(both, [clip, other], 0.5)
    assert step_name("nudge", both, shifted) == "nudge 2 clips by +0.5 s"


def test_tracks_markers_and_variants_are_named():
    p, track, _ = fan_knob()
    renamed = edits.set_track(p, track, name="Fan")
    assert step_name("rename track", p, renamed) == "rename track 'Torque 1' to 'Fan'"
    scaled = edits.set_track(p, track, full_scale=0.05)
    assert step_name("full scale", p, scaled) == "full scale of 'Torque 1' to 50 mNm"
    muted = edits.set_track(p, track, mute=True)
    assert step_name("mute", p, muted) == "mute 'Torque 1'"
    marked, index = markers.add_marker(p, 50 * DEG, "Lo")
    assert step_name("add marker", p, marked) == "add marker 'Lo' at 50°"
    moved = markers.move_marker(marked, index, 110 * DEG)
    assert step_name("move marker", marked, moved) == "move marker 'Lo' to 110°"
    saved = edits.save_variant(p, "A")
    assert step_name("save variant", p, saved) == "save variant A"
    two = edits.save_variant(saved, "B")
    assert step_name("switch variant", two, edits.switch_variant(two, "A")) == (
        "switch to variant A"
    )
    assert step_name("delete variant B", two, edits.remove_variant(two, "B")) == (
        "delete variant B"
    )


def test_the_history_keeps_labels_and_names_both():
    p, _, clip = fan_knob()
    history = History(p)
    base = history.project
    history.do("move clip", edits.move_clip(base, clip, 15 * DEG), merge_key="drag")
    history.do("move clip", edits.move_clip(base, clip, 20 * DEG), merge_key="drag")
    assert history.labels == ["open", "move clip"]
    assert history.names == ["open", "move 'detents copy' to 20°"]
    assert history.undo_name == "move 'detents copy' to 20°"
    history.undo()
    assert history.redo_name == "move 'detents copy' to 20°"
