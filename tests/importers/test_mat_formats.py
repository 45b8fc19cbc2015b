"""Octave's text format, Octave -hdf5 and MATLAB v7.3 .mat files, built here as those tools
write them, import like a v7 file."""

from __future__ import annotations

import h5py
import numpy as np
import pytest
import scipy.io

from timeline.files import importing
from timeline.plugins.file_formats import FormatError

VALUES = np.array([0.5, -0.25, 1.0, 0.125])


def _read(path, **options):
    return importing.read_file(path, **options).placements[0].tile


def test_octave_text_format(tmp_path):
    path = tmp_path / "o.mat"
    path.write_text(
        "# Created by Octave 8.4.0, Thu Nov 26 10:00:00 2026 UTC <me@host>\n"
        "# name: fs\n# type: scalar\n2000\n\n\n"
        "# name: note\n# type: sq_string\n# elements: 1\n# length: 5\nhello\n\n\n"
        "# name: shape\n# type: matrix\n# rows: 4\n# columns: 1\n 0.5\n -0.25\n 1\n 0.125\n\n\n"
        "# name: cube\n# type: matrix\n# ndims: 3\n 1 2 2\n 1\n 2\n 3\n 4\n\n\n"
    )
    tile = _read(path)
    assert tile.rate == 2000.0
    np.testing.assert_array_equal(tile.data, VALUES)


def test_octave_text_skips_structs_cells_and_complex_values(tmp_path):
    path = tmp_path / "s.mat"
    path.write_text(
        "# Created by Octave 8.4.0\n"
        "# name: shape\n# type: matrix\n# rows: 4\n# columns: 1\n 0.5\n -0.25\n 1\n 0.125\n\n\n"
        "# name: settings\n# type: scalar struct\n# ndims: 2\n 1 1\n# length: 2\n"
        "# name: shape\n# type: matrix\n# rows: 1\n# columns: 2\n 9 9\n\n\n"
        "# name: names\n# type: cell\n# rows: 1\n# columns: 1\n"
        "# name: <cell-element>\n# type: sq_string\n# elements: 1\n# length: 1\nx\n\n\n\n\n"
        "# name: z\n# type: complex matrix\n# rows: 1\n# columns: 2\n (1,2) (3,4)\n"
    )
    np.testing.assert_array_equal(_read(path, rate=100).data, VALUES)


def test_octave_text_row_vector_and_range(tmp_path):
    path = tmp_path / "r.mat"
    path.write_text(
        "# Created by Octave 8.4.0\n# name: t\n# type: range\n# base, limit, increment\n"
        "0 0.003 0.001\n\n\n# name: y\n# type: matrix\n# rows: 1\n# columns: 4\n"
        " 0.5 -0.25 1 0.125\n"
    )
    placement = importing.read_file(path).placements[0]
    assert placement.tile.rate == 1000.0
    np.testing.assert_array_equal(placement.tile.data, VALUES)


def test_a_truncated_octave_text_file_is_one_sentence(tmp_path):
    path = tmp_path / "cut.mat"
    path.write_text(
        "# Created by Octave 8.4.0\n# name: y\n# type: matrix\n# rows: 4\n# columns: 1\n 1\n"
    )
    with pytest.raises(FormatError, match="not a readable Octave text file"):
        _read(path, rate=100)


def test_octave_hdf5(tmp_path):
    path = tmp_path / "o.mat"
    with h5py.File(path, "w") as h5:
        for name, kind, value in (("shape", "matrix", VALUES.reshape(1, -1)),
                                  ("rate", "scalar", np.float64(500.0))):  # fmt: skip
            group = h5.create_group(name)
            group.attrs["OCTAVE_NEW_FORMAT"] = np.uint8(1)
            group.create_dataset("type", data=np.bytes_(kind))
            group.create_dataset("value", data=value)
    tile = _read(path)
    assert tile.rate == 500.0
    np.testing.assert_array_equal(tile.data, VALUES)


def test_matlab_v73(tmp_path):
    path = tmp_path / "m.mat"
    with h5py.File(path, "w", userblock_size=512) as h5:
        shape = h5.create_dataset("shape", data=VALUES.reshape(1, -1))  # 4 x 1, column-major
        shape.attrs["MATLAB_class"] = np.bytes_("double")
        time = h5.create_dataset("time", data=(np.arange(4) / 250.0).reshape(1, -1))
        time.attrs["MATLAB_class"] = np.bytes_("double")
        label = h5.create_dataset("label", data=np.array([[ord(c)] for c in "knob"], np.uint16))
        label.attrs["MATLAB_class"] = np.bytes_("char")
    header = b"MATLAB 7.3 MAT-file, Platform: GLNXA64, Created on: Thu Nov 26 10:00:00 2026 "
    header += b"HDF5 schema 1.00 ."
    with path.open("r+b") as f:
        f.write(header.ljust(124, b" ") + b"\x00\x02IM")
    tile = _read(path)
    assert tile.rate == 250.0
    np.testing.assert_array_equal(tile.data, VALUES)


@pytest.mark.parametrize(
    ("cut", "said"), [(100, "its data ends early or is damaged"), (150, "its data ends early")]
)
def test_a_truncated_v5_file_is_said_in_the_files_terms(tmp_path, cut, said):
    """scipy's 'index out of range' and 'could not read bytes' were passed on as they were
    (found by the hostile campaign)."""
    path = tmp_path / "m.mat"
    scipy.io.savemat(path, {"drive": VALUES, "fs": 250.0}, oned_as="column")
    path.write_bytes(path.read_bytes()[:cut])
    with pytest.raises(FormatError, match=rf"^m.mat is not a readable .mat file \({said}\)$"):
        _read(path)
