"""Generator parameters and tile lengths set exactly; templates are copied, not changed."""

from __future__ import annotations

import math

import pytest

from timeline import edits
from timeline.edits import tile_params
from timeline.errors import EditError
from timeline.tiles import generator, spline


def placed(tile, tab="Templates"):
    p = edits.new_project(templates=False)
    p, tile_id = edits.add_tile(p, tile, tab)
    p, track = edits.add_track(p, "drive")
    p, whole = edits.add_clip(p, track, tile_id, 0.0)
    p, part = edits.add_clip(p, track, tile_id, 2.0, source_in=0.1, source_out=0.4)
    return p, tile_id, whole, part


def test_set_param_changes_the_rendered_shape():
    p, tile_id, _, _ = placed(generator("sine", 1.0, frequency=5))
    p = tile_params.set_param(p, tile_id, "frequency", 12.0)
    tile = p.tile(tile_id)
    assert tile.param("frequency") == 12.0
    assert tile.evaluate([1 / 48])[0] == pytest.approx(1.0)
    with pytest.raises(EditError, match="no parameter 'duty'"):
        tile_params.set_param(p, tile_id, "duty", 0.3)
    with pytest.raises(EditError, match="finite"):
        tile_params.set_param(p, tile_id, "frequency", math.inf)


def test_an_impossible_value_is_one_sentence():
    p, tile_id, _, _ = placed(generator("chirp", 1.0, f0=5, f1=50, exponential=1))
    with pytest.raises(EditError, match="does not make a chirp"):
        tile_params.set_param(p, tile_id, "f0", 0.0)


def test_set_length_carries_whole_clips_and_keeps_parts():
    p, tile_id, whole, part = placed(spline([(0, 0), (0.5, 1), (1, 0)]))
    p = edits.set_fade(p, whole, "in", 0.4, "linear")
    p = edits.set_fade(p, whole, "out", 0.4, "linear")
    p = tile_params.set_length(p, tile_id, 0.5)
    c = p.find_clip(whole)[1]
    assert c.duration == pytest.approx(0.5)
    assert c.fade_in.length + c.fade_out.length == pytest.approx(0.5)  # fades fit the clip
    assert p.tile(tile_id).points == ((0, 0), (0.25, 1), (0.5, 0))
    assert p.find_clip(part)[1].duration == pytest.approx(0.3)
    with pytest.raises(EditError, match="plays this tile up to 0.4"):
        tile_params.set_length(p, tile_id, 0.3)
    with pytest.raises(EditError, match="positive"):
        tile_params.set_length(p, tile_id, 0.0)


def test_a_template_is_copied_and_only_the_chosen_clips_move_to_the_copy():
    p, tile_id, whole, part = placed(generator("sine", 1.0, frequency=5))
    p, copy = tile_params.editable(p, tile_id, [whole])
    assert copy != tile_id and copy in p.tab("Scratch").tile_ids
    assert p.tile(copy).name == "sine copy"
    assert p.find_clip(whole)[1].tile_id == copy
    assert p.find_clip(part)[1].tile_id == tile_id
    same, again = tile_params.editable(p, copy, [whole])
    assert again == copy and same is p
