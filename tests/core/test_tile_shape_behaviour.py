"""The waveform editor's point edits, editable copies and ranges, checked against hand values."""

from __future__ import annotations

import numpy as np
import pytest

from tests.core.test_vibration import _project as vibration_project
from tests.core.test_vibration import design_of
from timeline import edits
from timeline.edits import tile_shape
from timeline.errors import EditError
from timeline.model import Project
from timeline.tiles import SampledTile, SplineTile

LINE = ((0.0, 0.0), (0.5, 0.5), (1.0, 1.0))  # a natural spline through these is the line v = t


def _with(tile) -> tuple[Project, str]:  # noqa: ANN001
    project = edits.new_project(rate=1000.0, templates=False)
    project = edits.add_tab(project, "Mine")
    return edits.add_tile(project, tile)


def _points(project: Project, tile_id: str) -> tuple:
    return project.tile(tile_id).points


def test_the_first_and_last_points_move_within_the_tile() -> None:
    project, tile = _with(SplineTile(LINE, 1.0))
    moved = tile_shape.move_point(project, tile, 0, -0.3, 0.25)  # clamped to t = 0
    assert _points(moved, tile) == ((0.0, 0.25), (0.5, 0.5), (1.0, 1.0))
    moved = tile_shape.move_point(project, tile, 2, 7.0, -1.0)  # clamped to the duration
    assert _points(moved, tile) == ((0.0, 0.0), (0.5, 0.5), (1.0, -1.0))
    moved = tile_shape.move_point(project, tile, 1, 1.5, 2.0)  # 1 us before its neighbour
    assert _points(moved, tile)[1] == (1.0 - 1e-6, 2.0)
    with pytest.raises(EditError, match=r"^the tile has no point 4$"):
        tile_shape.move_point(project, tile, 3, 0.5, 0.5)


def test_a_point_is_added_at_the_tiles_start_and_refused_when_not_finite() -> None:
    project, tile = _with(SplineTile(((0.25, 1.0), (0.75, 2.0)), 1.0))
    added, index = tile_shape.add_point(project, tile, 0.0, 3.0)
    assert index == 0
    assert _points(added, tile) == ((0.0, 3.0), (0.25, 1.0), (0.75, 2.0))
    with pytest.raises(EditError, match=r"^a point needs finite numbers$"):
        tile_shape.add_point(project, tile, 0.5, float("nan"))


def test_a_point_added_to_a_design_keeps_its_value_within_0_to_1() -> None:
    project = vibration_project()
    tile = project.tracks[0].clips[0].tile_id
    project, index = tile_shape.add_point(project, tile, 0.9, 1.5)
    assert design_of(project).amplitude[index] == (0.9, 1.0)
    project, index = tile_shape.add_point(project, tile, 0.95, -0.5)
    assert design_of(project).amplitude[index] == (0.95, 0.0)


def test_the_last_point_stays() -> None:
    project, tile = _with(SplineTile(((0.5, 1.0),), 1.0))
    with pytest.raises(EditError, match=r"^a tile's shape needs at least one point$"):
        tile_shape.remove_point(project, tile, 0)


def test_an_editable_copy_of_samples_interpolates_them() -> None:
    """A ramp data[i] = i at 11 Hz (1 s): the copy's 12 points at t = j/11 s hold j."""
    project, tile = _with(SampledTile(np.arange(11.0), 11.0, "ramp"))
    copied, new = tile_shape.editable_copy(project, tile, "Mine")
    spline = copied.tile(new)
    assert spline.name == "ramp (edit)"
    assert new in copied.tab("Mine").tile_ids
    ts = [t for t, _ in spline.points]
    np.testing.assert_allclose(ts, np.arange(12) / 11, rtol=0, atol=1e-15)
    # interp at t * 11: j up to the last sample's 10 (the 12th point, t = 1 s, holds 10)
    np.testing.assert_allclose([v for _, v in spline.points], [*range(11), 10], atol=1e-12)


def test_a_range_of_a_spline_starts_and_ends_on_its_curve() -> None:
    tile = SplineTile(LINE, 1.0, name="line")
    part = tile_shape.range_tile(tile, 0.75, 0.25, 1000.0)  # the ends in either order
    assert part.name == "line 0.25-0.75 s"
    assert part.duration == 0.5
    np.testing.assert_allclose(part.points, [(0.0, 0.25), (0.25, 0.5), (0.5, 0.75)], atol=1e-12)
    with pytest.raises(EditError, match=r"^select a range of the tile first$"):
        tile_shape.range_tile(tile, 0.3, 0.3, 1000.0)


def test_a_range_goes_to_the_tab_asked_for_under_a_name_of_its_own() -> None:
    project, tile = _with(SplineTile(LINE, 1.0, name="line"))
    project, first = tile_shape.range_to_palette(project, tile, 0.25, 0.75, "Mine")
    project, second = tile_shape.range_to_palette(project, tile, 0.25, 0.75, "Mine")
    assert project.tab("Mine").tile_ids == (first, second)
    assert [project.tile(t).name for t in (first, second)] == [
        "line 0.25-0.75 s",
        "line 0.25-0.75 s 2",
    ]
