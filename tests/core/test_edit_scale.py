"""Edits touch only what they change: sorted insertion, shared tracks and tiles, stable files."""

from __future__ import annotations

import contextlib
import os
import subprocess
import sys

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from timeline import edits
from timeline.errors import EditError
from timeline.files import projectfile
from timeline.tiles import generator

from .test_edit_properties import OPS, apply, base_project


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(st.tuples(OPS, st.integers(0, 50)), max_size=14))
def test_tracks_stay_sorted_and_duration_is_the_last_end(steps):
    p = base_project()
    for op, pick in steps:
        with contextlib.suppress(EditError):
            p = apply(p, op, pick)
        for track in p.tracks:
            assert list(track.clips) == sorted(track.clips, key=lambda c: (c.start, c.id))
            assert track.clips_by_id == {c.id: c for c in track.clips}
        ends = [c.end for t in p.tracks for c in t.clips]
        assert p.duration == max(ends, default=0.0)


def test_an_edit_shares_the_tracks_and_tiles_it_does_not_touch():
    p = base_project()
    p, third = edits.add_track(p, "stiffness")
    clip = p.tracks[0].clips[0]
    moved = edits.move_clip(p, clip.id, 2.5)
    assert moved.tracks[1] is p.tracks[1] and moved.tracks[2] is p.tracks[2]
    assert moved.tiles is p.tiles
    across = edits.move_clip(p, clip.id, 0.25, third)
    assert across.tracks[1] is p.tracks[1]
    assert [c.id for c in across.track(third).clips] == [clip.id]
    assert across.tracks[0].clips == ()
    bigger, tile_id = edits.add_tile(p, generator("ramp", 0.5))
    assert set(bigger.tiles) == set(p.tiles) | {tile_id} and tile_id not in p.tiles


def test_inserting_at_equal_starts_orders_by_id():
    p = base_project()
    track = p.tracks[0].id
    sine = p.tracks[0].clips[0].tile_id
    ids = []
    for _ in range(11):  # c10 sorts before c9 as text: the order edits always used
        p, cid = edits.add_clip(p, track, sine, 3.0)
        ids.append(cid)
    at_three = [c.id for c in p.track(track).clips if c.start == 3.0]
    assert at_three == sorted(ids)


SAVE = """
from timeline import edits
from timeline.files import projectfile
from timeline.tiles import generator
p = edits.new_project(templates=True)
for f in range(30):
    p, _ = edits.add_tile(p, generator("sine", 1.0, frequency=5 + f))
print(projectfile.dumps(p), end="")
"""


def test_saved_bytes_do_not_depend_on_the_hash_seed():
    outputs = {
        subprocess.run(
            [sys.executable, "-c", SAVE],
            capture_output=True,
            text=True,
            check=True,
            env={**os.environ, "PYTHONHASHSEED": seed},
        ).stdout
        for seed in ("1", "2", "3")
    }
    assert len(outputs) == 1
    text = outputs.pop()
    assert text.index('"tile9"') < text.index('"tile10"')
    assert projectfile.dumps(projectfile.loads(text)) == text


def test_add_clips_in_one_pass_is_add_tile_and_add_clip_step_by_step():
    p = edits.new_project(templates=False)
    p, a = edits.add_track(p, "drive")
    p, b = edits.add_track(p, "drive")
    p, sine = edits.add_tile(p, generator("sine", 1.0, frequency=5.0))
    shared = generator("ramp", 0.5)
    items = [
        (a, shared, 2.0, {}),
        (b, sine, 0.25, {"gain": 0.5}),
        (a, generator("sine", 0.01, frequency=200.0), 0.0, {"source_out": 0.005}),
        (a, shared, 2.0, {"reverse": True}),  # the same tile object again, the same start
        (b, generator("constant", 0.2), 0.1, {}),
    ]
    step, ids = p, []
    added: dict[int, str] = {}
    for track, tile, start, fields in items:
        if not isinstance(tile, str) and id(tile) not in added:
            step, added[id(tile)] = edits.add_tile(step, tile)
        tile_id = tile if isinstance(tile, str) else added[id(tile)]
        step, clip = edits.add_clip(step, track, tile_id, start, **fields)
        ids.append(clip)
    bulk, bulk_ids = edits.add_clips(p, items)
    assert bulk == step and bulk_ids == ids
    with pytest.raises(EditError, match="would play"):
        edits.add_clips(p, [(a, sine, 0.0, {"source_out": 2.0})])
