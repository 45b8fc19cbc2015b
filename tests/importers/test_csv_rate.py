"""A CSV whose rate the time column cannot give: the header stays first, readers as documented."""

from __future__ import annotations

import re

import numpy as np
import pytest

from timeline.files import exporting, importing
from timeline.plugins.file_formats import FormatError, Layers

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


@pytest.mark.parametrize("header", ["# rate=10kHz", "% fs: 10kHz,", "# rate=10_k"])
def test_a_rate_comment_is_read_whole_or_refused(tmp_path, header):
    """Only its leading digits were read: `10kHz` was 10 Hz, `1_000` 1 Hz (a 2-value file
    lasted 2 s), without a word (found by the hostile campaign)."""
    path = tmp_path / "r.csv"
    path.write_text(f"{header}\n0.5\n-0.5\n")
    token = header.split("=")[-1].split(": ")[-1].rstrip(",")
    with pytest.raises(FormatError, match=re.escape(f"rate in r.csv is not a number ({token!r})")):
        importing.read_file(path)
    for header, rate in (("# rate=1_000", 1000.0), ("% fs: 2.5e3Hz,", 2500.0)):
        path.write_text(f"{header}\n0.5\n-0.5\n")  # Python's 1_000; a unit in hertz
        assert importing.read_file(path).placements[0].tile.rate == rate
