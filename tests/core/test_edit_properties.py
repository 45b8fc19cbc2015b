"""Hypothesis: random edit sequences undo back to the start; save/load round-trips exactly."""

import contextlib
from dataclasses import replace

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from timeline import edits
from timeline.edits.history import History
from timeline.errors import EditError
from timeline.files import projectfile
from timeline.tiles import SampledTile, generator

finite = st.floats(min_value=-10, max_value=10, allow_nan=False)
positive = st.floats(min_value=0.05, max_value=5)


def base_project():
    p = edits.new_project(templates=False)
    p, a = edits.add_track(p, "drive")
    p, b = edits.add_track(p, "damping")
    p, sine = edits.add_tile(p, generator("sine", 1.0, frequency=5))
    p, rec = edits.add_tile(p, SampledTile(np.linspace(-1, 1, 300), 1000.0))
    p, _ = edits.add_clip(p, a, sine, 0.0)
    p, _ = edits.add_clip(p, b, rec, 0.5)
    return p


OPS = st.one_of(
    st.tuples(st.just("move"), finite),
    st.tuples(st.just("move_track"), st.integers(0, 1)),
    st.tuples(st.just("gain"), finite),
    st.tuples(st.just("scale"), finite, finite),
    st.tuples(st.just("invert"), finite),
    st.tuples(st.just("reverse")),
    st.tuples(st.just("stretch"), positive, st.sampled_from(["squeeze", "repeat"])),
    st.tuples(
        st.just("fade"),
        st.sampled_from(["in", "out"]),
        st.floats(0, 0.3),
        st.sampled_from(["linear", "equal-power", "exponential", "s-curve"]),
    ),
    st.tuples(st.just("split"), st.floats(0.01, 0.99)),
    st.tuples(st.just("trim"), st.floats(0.0, 0.4)),
    st.tuples(st.just("duplicate")),
    st.tuples(st.just("remove")),
    st.tuples(st.just("merge")),
    st.tuples(st.just("mute")),
    st.tuples(st.just("variant"), st.sampled_from(["A", "B"])),
)


def apply(p, op, pick):
    clips = [c for t in p.tracks for c in t.clips]
    if not clips:
        return edits.add_clip(p, p.tracks[0].id, next(iter(p.tiles)), 0.0)[0]
    clip = clips[pick % len(clips)]
    name, *args = op
    if name == "move":
        return edits.move_clip(p, clip.id, start=args[0], track_id=p.tracks[pick % 2].id)
    if name == "move_track":
        return edits.move_track(p, p.tracks[0].id, args[0])
    if name == "gain":
        return edits.set_clip_gain(p, clip.id, args[0])
    if name == "scale":
        return edits.scale_clip(p, clip.id, args[0], args[1])
    if name == "invert":
        return edits.invert_clip(p, clip.id, args[0])
    if name == "reverse":
        return edits.reverse_clip(p, clip.id)
    if name == "stretch":
        return edits.stretch_clip(p, clip.id, args[0], args[1])
    if name == "fade":
        return edits.set_fade(p, clip.id, args[0], args[1] * clip.duration, args[2])
    if name == "split":
        return edits.split_clip(p, clip.id, clip.start + args[0] * clip.duration)[0]
    if name == "trim":
        return edits.trim_clip(p, clip.id, start=clip.start + args[0] * clip.duration)
    if name == "duplicate":
        return edits.duplicate_clip(p, clip.id)[0]
    if name == "remove":
        return edits.remove_clip(p, clip.id)
    if name == "merge":
        same = [c.id for t in p.tracks for c in t.clips if t.kind == p.find_clip(clip.id)[0].kind]
        return edits.merge_clips(p, same[:3])[0]
    if name == "mute":
        track = p.tracks[pick % 2]
        return edits.set_track(p, track.id, mute=not track.mute)
    if p.variants and args[0] in [v.name for v in p.variants]:
        return edits.switch_variant(p, args[0])
    return edits.save_variant(p, args[0])


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(st.tuples(OPS, st.integers(0, 50)), max_size=12))
def test_undo_back_to_the_start_restores_the_project(steps):
    start = base_project()
    history = History(start)
    states = [start]
    for op, pick in steps:
        try:
            p = apply(history.project, op, pick)
        except EditError:
            continue  # refused: nothing changed
        history.do(op[0], p)
        states.append(p)
    saved = {v.name for p in states for v in p.variants}  # no OPS deletes a variant
    for expected in reversed(states[:-1]):
        assert_design(history.undo(), expected, saved)
    assert_design(history.project, start, saved)
    assert history.modified == bool(saved)  # the saved file lacks the variants carried back
    for expected in states[1:]:
        assert_design(history.redo(), expected, saved)


def assert_design(got, expected, saved: set[str]) -> None:
    """The state undo or redo arrived at is `expected`, with every variant saved on the way
    (variants outlive undo: only their own deletion removes them)."""
    assert replace(got, variants=expected.variants) == expected
    assert {v.name for v in got.variants} == saved
    for variant in expected.variants:
        assert got.variant(variant.name) == variant


@settings(max_examples=40, deadline=None)
@given(st.lists(st.tuples(OPS, st.integers(0, 50)), max_size=8))
def test_save_and_load_round_trip_exactly(steps):
    p = base_project()
    for op, pick in steps:
        with contextlib.suppress(EditError):
            p = apply(p, op, pick)
    assert projectfile.loads(projectfile.dumps(p)) == p


@settings(max_examples=200, deadline=None)
@given(st.binary(max_size=300) | st.text(max_size=300).map(str.encode))
def test_arbitrary_bytes_give_a_project_or_one_clear_error(blob):
    try:
        projectfile.loads(blob)
    except projectfile.ProjectFileError as exc:
        assert "\n" not in str(exc)


json_values = st.recursive(
    st.none() | st.booleans() | st.integers() | st.floats(allow_nan=False) | st.text(max_size=5),
    lambda inner: (
        st.lists(inner, max_size=4) | st.dictionaries(st.text(max_size=6), inner, max_size=4)
    ),
    max_leaves=20,
)


@settings(max_examples=200, deadline=None)
@given(json_values)
def test_arbitrary_json_in_a_project_body_gives_one_clear_error(body):
    import json

    doc = {"format": "haptic-timeline", "schema": 1, "project": body, "media": {}}
    try:
        projectfile.loads(json.dumps(doc))
    except projectfile.ProjectFileError as exc:
        assert "\n" not in str(exc)


def test_history_merges_a_drag_into_one_step():
    p = base_project()
    clip = p.tracks[0].clips[0].id
    h = History(p)
    for x in (0.1, 0.2, 0.3):
        h.do("move", edits.move_clip(p, clip, start=x), merge_key=("drag", clip))
    assert len(h) == 2 and h.project.find_clip(clip)[1].start == 0.3
    assert h.undo() == p


def test_switching_variant_keeps_tiles_made_since_in_the_library():
    p = edits.save_variant(base_project(), "A")
    merged, tile_id = edits.merge_clips(p, [p.tracks[0].clips[0].id])
    back = edits.switch_variant(merged, "A")
    assert back.tracks == p.tracks  # the design of A
    assert tile_id in back.tiles and tile_id in back.tab("Scratch").tile_ids
    assert projectfile.loads(projectfile.dumps(back)) == back


@settings(max_examples=50, deadline=None)
@given(
    st.lists(
        st.tuples(st.integers(0, 1), st.floats(0.0, 3.0).map(lambda t: round(t, 2))),
        min_size=1,
        max_size=12,
    ),
    st.sets(st.integers(0, 13)),
    st.floats(-2.0, 2.0).map(lambda t: round(t, 2)),
)
def test_shifting_clips_at_once_is_moving_each_in_turn(placed, chosen, shift):
    p = base_project()
    tracks = [t.id for t in p.tracks]
    sine = p.tracks[0].clips[0].tile_id
    for track, start in placed:  # equal starts included: the order is then by id
        p, _ = edits.add_clip(p, tracks[track], sine, start)
    ids = [c.id for t in p.tracks for c in t.clips]
    moving = [ids[k] for k in sorted(chosen) if k < len(ids)]
    one_by_one = p
    for clip_id in moving:
        start = one_by_one.find_clip(clip_id)[1].start
        one_by_one = edits.move_clip(one_by_one, clip_id, start + shift)
    assert edits.shift_clips(p, moving, shift).tracks == one_by_one.tracks
