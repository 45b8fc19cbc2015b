"""Tile shape edits: spline points, replacing a tile, ranges to the palette."""

import numpy as np
import pytest

from timeline import edits, render
from timeline.edits import tile_shape
from timeline.errors import EditError
from timeline.tiles import SampledTile, generator, spline

from .helpers import one_clip


def test_moving_a_spline_point_changes_the_render_at_that_time():
    p, clip = one_clip(spline([(0, 0), (0.5, 1), (1, 0)], 1.0, "pchip"))
    tile_id = p.find_clip(clip)[1].tile_id
    p2 = tile_shape.move_point(p, tile_id, 1, 0.5, -0.5)
    assert render(p2)["drive"][5000] == pytest.approx(-0.5 * 0.18)
    p3, index = tile_shape.add_point(p2, tile_id, 0.25, 2.0)
    assert index == 1 and render(p3)["drive"][2500] == pytest.approx(2.0 * 0.18)
    p4 = tile_shape.remove_point(p3, tile_id, index)
    assert p4.tile(tile_id) == p2.tile(tile_id)
    with pytest.raises(EditError, match="already a point"):
        tile_shape.add_point(p2, tile_id, 0.5, 1.0)


def test_a_point_is_kept_between_its_neighbours():
    p, clip = one_clip(spline([(0, 0), (0.5, 1), (1, 0)], 1.0))
    tile_id = p.find_clip(clip)[1].tile_id
    moved = tile_shape.move_point(p, tile_id, 1, 5.0, 1.0).tile(tile_id)
    assert moved.points[1][0] == pytest.approx(1.0 - 1e-6)


def test_replace_tile_refuses_a_shape_shorter_than_its_clips():
    p, clip = one_clip(SampledTile(np.ones(1000), 10_000.0))
    tile_id = p.find_clip(clip)[1].tile_id
    with pytest.raises(EditError, match="cannot end at"):
        edits.replace_tile(p, tile_id, SampledTile(np.ones(10), 10_000.0))
    p2 = edits.replace_tile(p, tile_id, SampledTile(np.full(1000, 0.5), 10_000.0))
    assert render(p2)["drive"][500] == pytest.approx(0.09)


def test_range_to_palette_and_editable_copy():
    p, clip = one_clip(generator("ramp", 1.0, start=0.0, end=1.0))
    tile_id = p.find_clip(clip)[1].tile_id
    p2, part = tile_shape.range_to_palette(p, tile_id, 0.25, 0.5)
    tile = p2.tile(part)
    assert part in p2.tab("Scratch").tile_ids and tile.duration == pytest.approx(0.25)
    assert tile.data[0] == pytest.approx(0.25) and tile.data[-1] == pytest.approx(0.4999)
    p3, copy = tile_shape.editable_copy(p, tile_id)
    points = p3.tile(copy).points
    assert len(points) == tile_shape.EDITABLE_POINTS
    assert points[-1] == pytest.approx((1.0, 1.0))


def test_remove_and_rename_tiles_and_variants():
    p, clip = one_clip(generator("sine", 1.0))
    used = p.find_clip(clip)[1].tile_id
    with pytest.raises(EditError, match="used by 1 clip"):
        edits.remove_tile(p, used)
    p, spare = edits.add_tile(p, generator("ramp", 1.0))
    gone = edits.remove_tile(p, spare)
    assert spare not in gone.tiles and spare not in gone.tab("Scratch").tile_ids
    assert edits.rename_tile(p, used, "hum").tile(used).name == "hum"
    p = edits.save_variant(p, "A")
    q = edits.remove_variant(p, "A")
    assert q.variants == () and q.active_variant is None
    with pytest.raises(EditError, match="no variant"):
        edits.switch_variant(q, "A")
