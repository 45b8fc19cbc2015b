"""Render, then import: every format the project writes gives back its layers' values and kinds."""

from __future__ import annotations

import math

import numpy as np
import pytest

from timeline import edits, generator
from timeline.files import exporting, importing
from timeline.rendering import mixer

FORMATS = [".csv", ".txt", ".mat", ".npz", ".wav"]


def _time_project():
    """Drive, stiffness, damping and mass, each a different clip (damping peaks at 3e-5)."""
    p = edits.new_project("time")
    for kind, gain in (("drive", 0.8), ("stiffness", 0.3), ("damping", 0.3), ("mass", 0.5)):
        p, track = edits.add_track(p, kind, kind)
        p, tile = edits.add_tile(p, generator("sine", 0.02, kind, frequency=100.0))
        p, _ = edits.add_clip(p, track, tile, 0.0, gain=gain)
    return p


def _position_project():
    p = edits.new_project("position")
    p, track = edits.add_track(p, "torque", "torque")
    p, tile = edits.add_tile(p, generator("sine", math.radians(20.0), "detent", frequency=5.0))
    p, _ = edits.add_clip(p, track, tile, 0.0, gain=0.6)
    return p


def _round_trip(project, path):
    exporting.export_project(project, path)
    back, _ = importing.import_file(edits.new_project(project.axis), path)
    before = mixer.render(project, 0.0, project.duration)
    after = mixer.render(back, 0.0, project.duration)
    return before, after, [t.kind for t in back.tracks]


@pytest.mark.parametrize("ext", FORMATS)
def test_time_layers_come_back_on_their_kinds_at_their_values(tmp_path, ext):
    project = _time_project()
    before, after, kinds = _round_trip(project, tmp_path / f"p{ext}")
    assert kinds == ["drive", "stiffness", "damping", "mass"]
    assert set(after) == set(before)
    tolerance = 6e-8 if ext == ".wav" else 0.0  # float32 samples in a FLOAT WAV
    for kind, values in before.items():
        np.testing.assert_allclose(after[kind], values, rtol=tolerance, atol=0)
    assert np.abs(after["drive"]).max() == pytest.approx(0.8 * 0.18, rel=1e-3)


@pytest.mark.parametrize("ext", [".csv", ".txt", ".mat", ".npz"])
def test_position_layers_come_back_with_the_axis_in_degrees(tmp_path, ext):
    project = _position_project()
    before, after, kinds = _round_trip(project, tmp_path / f"p{ext}")
    assert kinds == ["torque"]
    np.testing.assert_array_equal(after["torque"], before["torque"])


def test_the_csv_states_its_kinds_units_and_degrees(tmp_path):
    exporting.export_project(_position_project(), tmp_path / "p.csv")
    lines = (tmp_path / "p.csv").read_text().splitlines()
    assert lines[0] == "angle_deg,torque"
    assert float(lines[-2].split(",")[0]) == pytest.approx(19.99)  # 100 samples per degree
    assert lines[-1].startswith("# haptic-timeline units: angle_deg=deg torque=N*m rate=")
    with np.load(_npz(tmp_path)) as npz:
        assert npz["angle_deg"][-1] == pytest.approx(19.99) and "torque=N*m" in str(npz["units"])


def _npz(tmp_path):
    exporting.export_project(_position_project(), tmp_path / "p.npz")
    return tmp_path / "p.npz"


def test_a_foreign_table_is_a_shape_with_a_note(tmp_path):
    (tmp_path / "scope.csv").write_text("time,drive\n0,1\n0.001,0.5\n")
    imported = importing.read_file(tmp_path / "scope.csv")
    assert imported.placements[0].kind is None
    assert list(imported.placements[0].tile.data) == [1.0, 0.5]
    assert "unitless shape" in imported.notes[0]


def test_an_old_radian_table_still_reads_in_radians(tmp_path):
    (tmp_path / "old.csv").write_text("angle,torque\n0.5,1\n0.75,2\n")
    placement = importing.read_file(tmp_path / "old.csv").placements[0]
    assert placement.start == 0.5 and placement.tile.rate == 4.0
