"""Undo step names and variant history, spans covered by other clips, a refusal's wording."""

import pytest

from timeline import edits
from timeline.edits import tile_params
from timeline.edits.history import History
from timeline.edits.placement import overlaps
from timeline.edits.step_names import step_name
from timeline.edits.vibration import Emphasis, emphasis_tile
from timeline.errors import EditError
from timeline.tiles import GeneratorTile


def _tap(tracks: int = 1):
    """A project of `tracks` drive tracks with a 0.1 s 'tap' clip at 1 s on the first."""
    p = edits.new_project(templates=False)
    ids = []
    for _ in range(tracks):
        p, track = edits.add_track(p, "drive")
        ids.append(track)
    p, tile = edits.add_tile(p, GeneratorTile("sine", 0.1, (("frequency", 30.0),), "tap"))
    p, clip = edits.add_clip(p, ids[0], tile, 1.0)
    return p, ids, tile, clip


def test_a_recorded_step_is_named_from_the_state_before_it():
    p, _, _, clip = _tap()
    h = History(p)
    h.do("move clip", edits.move_clip(p, clip, 2.0))
    assert h.names == ["open", "move 'tap' to 2 s"] and h.undo_name == "move 'tap' to 2 s"


def test_redoing_several_deletions_removes_every_deleted_variant():
    p, _, _, _ = _tap()
    p = edits.save_variant(edits.save_variant(p, "A"), "B")
    h = History(p)
    h.do("delete variant", edits.remove_variant(h.project, "A"))
    h.do("delete variant", edits.remove_variant(h.project, "B"))
    assert [v.name for v in h.go_to(0).variants] == ["A", "B"]
    assert h.go_to(2).variants == ()
    h.go_to(0)
    assert [v.name for v in h.redo().variants] == ["B"]


def test_a_step_on_one_of_many_tracks_is_named_for_its_clip():
    # the untouched tracks are skipped, not a reason to stop looking
    p, ids, _, clip = _tap(tracks=40)
    assert step_name("move clip", p, edits.move_clip(p, clip, 1.5)) == "move 'tap' to 1.5 s"
    p, last = edits.add_clip(p, ids[-1], p.find_clip(clip)[1].tile_id, 3.0)
    assert step_name("gain", p, edits.set_clip_gain(p, last, 0.5)) == (
        "gain of 'tap' to x0.5 (-6.0 dB)"
    )


def test_a_change_plus_an_addition_that_is_no_split_keeps_the_label():
    p, ids, tile, clip = _tap()
    after = edits.move_clip(p, clip, 2.0)
    after, added = edits.add_clip(after, ids[0], tile, 3.0)
    assert step_name("paste", p, after) == "paste"
    moved_and_removed = edits.remove_clip(edits.move_clip(after, clip, 1.0), added)
    assert step_name("edit", after, moved_and_removed) == "edit"


def test_an_offset_change_is_named_as_the_clip_s_amplitude():
    p, _, _, clip = _tap()
    after = edits.set_clip(p, clip, offset=0.1)
    assert step_name("clip fields", p, after) == "amplitude of 'tap' to x1 (+0.0 dB)"


def test_removing_two_tracks_at_once_keeps_the_label():
    p, ids, _, _ = _tap(tracks=3)
    after = edits.remove_track(edits.remove_track(p, ids[1]), ids[2])
    assert step_name("delete tracks", p, after) == "delete tracks"
    assert step_name("delete", p, edits.remove_track(p, ids[1])) == "remove track 'Drive 2'"


def test_changing_two_tracks_at_once_keeps_the_label():
    p, ids, _, _ = _tap(tracks=2)
    after = edits.set_track(edits.set_track(p, ids[0], gain=0.5), ids[1], gain=0.5)
    assert step_name("tracks gain", p, after) == "tracks gain"
    assert step_name("gain", p, edits.set_track(p, ids[1], gain=0.5)) == (
        "gain of 'Drive 2' to x0.5 (-6.0 dB)"
    )


def test_the_span_covered_in_a_clip_reaches_to_the_furthest_later_end():
    q = edits.new_project(templates=False)
    q, track = edits.add_track(q, "drive")
    q, tile = edits.add_tile(q, GeneratorTile("sine", 1.0, (("frequency", 30.0),), "s"))
    q, a = edits.add_clip(q, track, tile, 0.0)
    q = edits.stretch_clip(q, a, 10.0)  # 0..10
    q, b = edits.add_clip(q, track, tile, 2.0)
    q = edits.stretch_clip(q, b, 3.0)  # 2..5
    assert overlaps(q, track) == {a: ((2.0, 5.0),), b: ((2.0, 5.0),)}
    q, _ = edits.add_clip(q, track, tile, 3.0)  # 3..4, inside both
    assert overlaps(q, track)[a] == ((2.0, 5.0),)


def test_a_generator_tile_s_length_refusal_says_what_to_change():
    p = edits.new_project(templates=False)
    p, tile = edits.add_tile(p, emphasis_tile(Emphasis(0.0, 1.0, 1.0)))
    message = "a emphasis lasts 0.00869565 s, as its parameters say; change those instead"
    with pytest.raises(EditError) as refused:
        tile_params.set_length(p, tile, 0.5)
    assert str(refused.value) == message
