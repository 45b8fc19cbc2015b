"""Edits named by mutation testing: placing a tile in a tab, merging clips across track gains."""

from __future__ import annotations

import numpy as np

from timeline import edits
from timeline.rendering.mixer import Mixer
from timeline.tiles import SampledTile

RATE = 10_000.0


def test_placing_a_tile_in_another_tab_shows_it_there_once() -> None:
    project = edits.new_project(rate=RATE, templates=False)
    project = edits.add_tab(project, "Mine")
    project, tile = edits.add_tile(project, SampledTile(np.ones(4), RATE))
    assert tile not in project.tab("Mine").tile_ids
    placed = edits.place_tile(project, tile, "Mine")
    assert placed.tab("Mine").tile_ids == (tile,)
    assert placed.tab("Scratch").tile_ids == project.tab("Scratch").tile_ids
    assert edits.place_tile(placed, tile, "Mine") is placed


def test_merging_clips_on_tracks_of_different_gains_renders_the_same() -> None:
    """The merged tile holds each clip scaled by its track's scale over the target track's."""
    project = edits.new_project(rate=RATE, templates=False)
    project, loud = edits.add_track(project, "drive")
    project, soft = edits.add_track(project, "drive")
    project = edits.set_track(project, soft, gain=0.25)
    project = edits.set_track(project, loud, gain=2.0)
    project, a = edits.add_tile(project, SampledTile(np.array([1.0, 2.0, 3.0]), RATE))
    project, b = edits.add_tile(project, SampledTile(np.array([4.0, 8.0]), RATE))
    project, first = edits.add_clip(project, loud, a, 10 / RATE)
    project, second = edits.add_clip(project, soft, b, 11 / RATE)
    before = Mixer().render(project, 0.0, 20 / RATE)["drive"]
    merged, tile = edits.merge_clips(project, [first, second])
    # the loud track (the earliest clip's) holds it: 4 * 0.25 / 2 = 0.5, 8 * 0.25 / 2 = 1
    assert merged.tile(tile).data.tolist() == [1.0, 2.5, 4.0]
    after = Mixer().render(merged, 0.0, 20 / RATE)["drive"]
    assert [c.start for c in merged.track(loud).clips] == [10 / RATE]
    assert not merged.track(soft).clips
    np.testing.assert_allclose(after, before, rtol=1e-15, atol=0.0)
