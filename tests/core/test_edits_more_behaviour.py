"""Edits named by the edits mutation run: palette tabs, variants, track and clip refusals (each
one sentence), a split's fades and a merge's tile name."""

from __future__ import annotations

import numpy as np
import pytest

from timeline import edits
from timeline.edits import tile_params
from timeline.edits.placement import into_gap
from timeline.errors import EditError
from timeline.model import Fade, Project
from timeline.tiles import SampledTile, SplineTile

RATE = 1000.0


def _project() -> tuple[Project, str, str]:
    project = edits.new_project(rate=RATE, templates=False)
    project, track = edits.add_track(project, "drive")
    project, tile = edits.add_tile(project, SampledTile(np.arange(1.0, 11.0), RATE, "ramp"))
    project, clip = edits.add_clip(project, track, tile, 0.0)  # 10 samples: 0 to 0.01 s
    return project, track, clip


def test_a_user_tab_is_renamed_and_removed() -> None:
    project = edits.add_tab(_project()[0], "Mine")
    renamed = edits.rename_tab(project, "Mine", "Yours")
    assert [t.name for t in renamed.palette] == ["Templates", "Scratch", "Yours"]
    with pytest.raises(EditError, match=r"^a palette tab cannot be called '  '$"):
        edits.rename_tab(project, "Mine", "  ")
    assert [t.name for t in edits.remove_tab(project, "Mine").palette] == ["Templates", "Scratch"]


def test_a_saved_variant_is_the_active_one_and_switching_back_restores_its_tiles() -> None:
    project, _, clip = _project()
    saved = edits.save_variant(project, "A")
    assert saved.active_variant == "A"
    tile_id = project.find_clip(clip)[1].tile_id
    changed = edits.replace_tile(saved, tile_id, SampledTile(np.zeros(10), RATE, "ramp"))
    back = edits.switch_variant(edits.save_variant(changed, "B"), "A")
    assert back.tile(tile_id).data.tolist() == list(np.arange(1.0, 11.0))


@pytest.mark.parametrize(("key", "words"), [("gain", "gain"), ("full_scale", "full scale")])
def test_a_track_setting_must_be_finite(key: str, words: str) -> None:
    project, track, _ = _project()
    with pytest.raises(EditError, match=rf"^a track's {words} must be a finite number$"):
        edits.set_track(project, track, **{key: float("nan")})


def test_clip_refusals_are_one_sentence_each() -> None:
    project, _, clip = _project()
    with pytest.raises(EditError, match=r"^a clip's id and tile cannot be changed this way$"):
        edits.set_clip(project, clip, id="other")
    with pytest.raises(EditError, match=r"^a fade of 0\.02 is longer than the clip \(0\.01\)$"):
        edits.set_fade(project, clip, "in", 0.02)
    with pytest.raises(EditError, match=r"^select at least one clip to merge$"):
        edits.merge_clips(project, [])


def test_a_split_keeps_the_fade_in_on_the_left_and_the_fade_out_on_the_right() -> None:
    project, _, clip = _project()
    project = edits.set_fade(project, clip, "in", 0.002)
    project = edits.set_fade(project, clip, "out", 0.003)
    split, right = edits.split_clip(project, clip, 0.005)
    left, after = split.find_clip(clip)[1], split.find_clip(right)[1]
    assert (left.fade_in, left.fade_out) == (Fade(0.002), Fade())
    assert (after.fade_in, after.fade_out) == (Fade(), Fade(0.003))
    assert (left.start, left.end, after.start, after.end) == (0.0, 0.005, 0.005, 0.01)


def test_a_merged_tile_is_named_merged() -> None:
    project, _, clip = _project()
    merged, tile = edits.merge_clips(project, [clip])
    assert merged.tile(tile).name == "merged"
    assert merged.tile(tile).data.tolist() == list(np.arange(1.0, 11.0))


def test_new_clips_move_together_into_the_first_gap_that_holds_them() -> None:
    """An old clip covers 0-0.01 s; two new ones at 0.005 and 0.012 s (0.017 s of material)
    move by 0.005 s, so the first starts where the old one ends, and keep their spacing."""
    project, track, old = _project()
    tile = project.find_clip(old)[1].tile_id
    project, a = edits.add_clip(project, track, tile, 0.005)
    project, b = edits.add_clip(project, track, tile, 0.012)
    moved = into_gap(project, [a, b], 0.005)
    assert moved.find_clip(a)[1].start == pytest.approx(0.01, abs=1e-12)
    assert moved.find_clip(b)[1].start == pytest.approx(0.017, abs=1e-12)
    assert moved.find_clip(old)[1].start == 0.0


def test_a_longer_spline_spreads_its_points_in_proportion() -> None:
    project = edits.new_project(rate=RATE, templates=False)
    project, tile = edits.add_tile(project, SplineTile(((0.0, 0.0), (0.25, 1.0), (0.5, 0.0)), 0.5))
    longer = tile_params.set_length(project, tile, 2.0)
    assert longer.tile(tile).points == ((0.0, 0.0), (1.0, 1.0), (2.0, 0.0))
    assert longer.tile(tile).duration == 2.0
