"""A CSV whose rate the time column cannot give: the header stays first, readers as documented."""

from __future__ import annotations

import numpy as np
import pytest

from timeline.files import exporting, importing
from timeline.plugins.file_formats import Layers

RATE = 10_000 / 3  # 3333.33... Hz: the time column alone rounds it
DRIVE = np.sin(np.arange(50) / 7.0)


@pytest.fixture
def written(tmp_path):
    path = tmp_path / "odd.csv"
    exporting.write_layers(Layers({"drive": DRIVE}, RATE), path)
    return path


def test_header_first_and_the_rate_in_a_trailing_comment(written):
    lines = written.read_text().splitlines()
    assert lines[0] == "time,drive" and lines[-1] == f"# rate={RATE!r}"
    tile = importing.read_file(written).placements[0].tile
    assert tile.rate == RATE and np.array_equal(tile.data, DRIVE)


def test_numpy_reads_it_with_the_documented_calls(written):
    table = np.loadtxt(written, delimiter=",", skiprows=1)
    assert table.shape == (50, 2) and np.array_equal(table[:, 1], DRIVE)
    named = np.genfromtxt(written, delimiter=",", names=True, comments="#")
    assert named.dtype.names == ("time", "drive") and np.array_equal(named["drive"], DRIVE)


def test_pandas_reads_it_with_the_documented_call(written):
    pd = pytest.importorskip("pandas")
    frame = pd.read_csv(written, comment="#")
    assert list(frame.columns) == ["time", "drive"]
    assert np.array_equal(frame["drive"].to_numpy(), DRIVE)


def test_the_txt_file_keeps_a_plain_matrix_for_matlab_load(tmp_path):
    path = tmp_path / "odd.txt"
    exporting.write_layers(Layers({"drive": DRIVE}, RATE), path)
    lines = path.read_text().splitlines()
    assert lines[0] == "% time\tdrive" and lines[-1] == f"% rate={RATE!r}"
    assert np.loadtxt(path, comments="%").shape == (50, 2)  # what Matlab's load does
    assert importing.read_file(path).placements[0].tile.rate == RATE
