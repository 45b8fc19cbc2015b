"""CSV/TXT and .mat: exact tile round trips, Matlab-style edits, headers, columns, rates."""

from __future__ import annotations

import io
import tempfile
from pathlib import Path
from unittest.mock import patch

import numpy as np
import pytest
import scipy.io
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from importers import text
from timeline import edits
from timeline.files import exporting, importing
from timeline.plugins.file_formats import FormatError, Layers
from timeline.rendering import mixer
from timeline.tiles import SampledTile

RNG = np.random.default_rng(3)


def _tile(rate: float = 1234.5, n: int = 300) -> SampledTile:
    return SampledTile(RNG.normal(size=n), rate, "shape")


def _read(path, **options) -> SampledTile:
    return importing.read_file(path, **options).placements[0].tile


@pytest.mark.parametrize("ext", [".csv", ".txt", ".mat"])
@pytest.mark.parametrize("rate", [10000.0, 44100.0, 1234.5, 10000 / 3, 5729.577951308232])
def test_tile_round_trip_is_exact(tmp_path, ext, rate):
    tile = _tile(rate)
    exporting.export_tile(tile, tmp_path / f"t{ext}")
    back = _read(tmp_path / f"t{ext}")
    assert back.rate == rate
    np.testing.assert_array_equal(back.data, tile.data)


def test_matlab_style_edit_reloads_into_the_same_tile(tmp_path):
    tile = _tile(2000.0)
    exporting.export_tile(tile, tmp_path / "t.mat")
    m = scipy.io.loadmat(tmp_path / "t.mat")
    m["value"] = np.flipud(m["value"]) * 0.5 + 0.1  # what a user does in Matlab
    scipy.io.savemat(tmp_path / "t.mat", {k: v for k, v in m.items() if not k.startswith("__")})
    back = _read(tmp_path / "t.mat")
    assert back.rate == 2000.0
    np.testing.assert_array_equal(back.data, tile.data[::-1] * 0.5 + 0.1)


def test_project_export_has_named_layers_and_time(tmp_path):
    project = edits.new_project()
    project, drive = edits.add_track(project, "drive")
    project, stiff = edits.add_track(project, "stiffness")
    project, tid = edits.add_tile(project, _tile(10000.0, 500))
    project, _ = edits.add_clip(project, drive, tid, 0.0)
    project, _ = edits.add_clip(project, stiff, tid, 0.01)
    layers = mixer.render(project, 0.0, project.duration)
    exporting.export_project(project, tmp_path / "p.mat")
    m = scipy.io.loadmat(tmp_path / "p.mat")
    np.testing.assert_array_equal(m["drive"][:, 0], layers["drive"])
    np.testing.assert_array_equal(m["stiffness"][:, 0], layers["stiffness"])
    assert m["time"][1, 0] == 1e-4 and m["rate"][0, 0] == 10000.0
    back = _read(tmp_path / "p.mat", column="stiffness")
    np.testing.assert_array_equal(back.data, layers["stiffness"])
    exporting.export_project(project, tmp_path / "p.csv")
    np.testing.assert_array_equal(_read(tmp_path / "p.csv").data, layers["drive"])
    np.testing.assert_array_equal(
        _read(tmp_path / "p.csv", column="stiffness").data, layers["stiffness"]
    )


@pytest.mark.parametrize(
    "text",
    [
        "# recorded on a scope\ntime,value\n0,1\n0.001,2\n0.002,3\n",
        "time\tvalue\n0\t1\n0.001\t2\n0.002\t3\n",
        "% time value\n0 1\n0.001 2\n0.002 3\n",
        "0;1\n0.001;2\n0.002;3\n",
        "0, 1\n\n0.001, 2\n// note\n0.002, 3\n",
    ],
)
def test_two_column_dialects(tmp_path, text):
    (tmp_path / "a.csv").write_text(text)
    tile = _read(tmp_path / "a.csv")
    assert tile.rate == 1000.0
    np.testing.assert_array_equal(tile.data, [1.0, 2.0, 3.0])


def test_one_column_needs_a_rate(tmp_path):
    (tmp_path / "a.txt").write_text("value\n0.5\n-0.25\n")
    with pytest.raises(FormatError, match="give its rate"):
        _read(tmp_path / "a.txt")
    tile = _read(tmp_path / "a.txt", rate=500)
    assert tile.rate == 500 and list(tile.data) == [0.5, -0.25]


def test_time_offset_becomes_the_clip_start(tmp_path):
    (tmp_path / "a.csv").write_text("time,drive\n0.5,1\n0.75,2\n")
    placement = importing.read_file(tmp_path / "a.csv").placements[0]
    assert placement.start == 0.5 and placement.tile.rate == 4.0


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("time,value\n0,1\n0.1,2\n0.3,3\n", "not evenly spaced"),
        ("time,value\n0,1\n0.1,nan\n", "not a finite number"),
        ("time,value\n0,1\n0.1\n", "not all numbers"),
        ("# only a comment\n", "no data rows"),
        ("time,value\n", "no data rows"),
    ],
)
def test_bad_tables_are_one_sentence(tmp_path, text, message):
    (tmp_path / "a.csv").write_text(text)
    with pytest.raises(FormatError, match=message):
        _read(tmp_path / "a.csv")


def test_unknown_column_names_the_choices(tmp_path):
    (tmp_path / "a.csv").write_text("time,drive\n0,1\n1,2\n")
    with pytest.raises(FormatError, match=r"columns: time, drive"):
        _read(tmp_path / "a.csv", column="mass")


def test_matlab_v73_is_refused_clearly(tmp_path):
    (tmp_path / "a.mat").write_bytes(b"MATLAB 7.3 MAT-file, Platform: x" + b"\0" * 200)
    with pytest.raises(FormatError, match="v7.3"):
        _read(tmp_path / "a.mat")


@settings(max_examples=60, deadline=None)
@given(
    st.lists(
        arrays(np.float64, st.integers(1, 12), elements=st.floats(allow_nan=False, width=64)),
        min_size=1,
        max_size=3,
    ),
    st.sampled_from([10000.0, 1234.5, 10000 / 3]),
    st.sampled_from([".csv", ".txt"]),
    st.sampled_from([1, 5, 4096]),
)
def test_written_tables_are_the_bytes_numpy_savetxt_writes(columns, rate, ext, block):
    layers = Layers({f"layer{k}": c for k, c in enumerate(columns)}, rate, 0.25)
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / f"t{ext}"
        with patch.object(text, "ROW_BLOCK", block):
            exporting.write_layers(layers, path)
        table = np.zeros((layers.length, 1 + len(columns)))
        table[:, 0] = 0.25 + np.arange(layers.length) / rate
        for k, c in enumerate(columns, start=1):
            table[: len(c), k] = c
        names = ["time", *layers.columns]
        csv = ext == ".csv"
        footer = "" if text._axis_gives_rate(table[:, 0], rate) else f"rate={rate!r}"
        expected = io.StringIO()
        np.savetxt(
            expected,
            table,
            fmt="%.17g",
            delimiter="," if csv else "\t",
            header=("," if csv else "\t").join(names),
            footer=("# " if csv and footer else "") + footer,
            comments="" if csv else "% ",
        )
        assert path.read_text(encoding="utf-8") == expected.getvalue()
