"""MATLAB v7.3 and Octave `-hdf5` .mat files through h5py: their numeric variables as arrays.

* MATLAB v7.3 is an HDF5 file behind a 512-byte user block that begins "MATLAB 7.3 MAT-file";
  each variable is a dataset named after it, with a MATLAB_class attribute ("double", "int16",
  "char", ...); arrays are stored column-major, so h5py sees an N x 1 vector as 1 x N.
* Octave's `save -hdf5` writes a plain HDF5 file; each variable is a group named after it that
  holds a `type` string ("matrix", "scalar", ...) and a `value` dataset, also column-major.

Only real numeric arrays are kept (strings, structs, cells and complex values are skipped), in
Matlab's orientation (rows x columns), as scipy.io.loadmat gives them.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

HDF5_SIGNATURE = b"\x89HDF\r\n\x1a\n"
MATLAB_73 = b"MATLAB 7.3 MAT-file"
NUMERIC_CLASSES = {"double", "single", "logical", "int8", "int16", "int32", "int64", "uint8",
                   "uint16", "uint32", "uint64"}  # fmt: skip
OCTAVE_NUMERIC = {"scalar", "matrix", "bool", "bool matrix"}


def is_hdf5(head: bytes) -> bool:
    """True for an HDF5 file: the signature at 0 (Octave) or after a 512-byte user block."""
    return head[:8] == HDF5_SIGNATURE or head[512:520] == HDF5_SIGNATURE


def _matlab_order(data: np.ndarray) -> np.ndarray:
    """HDF5's row-major view of a column-major array, turned back to Matlab's rows x columns."""
    return data.T if data.ndim >= 2 else data.reshape(1, -1) if data.ndim == 1 else data


def _text(value: Any) -> str:
    """An attribute's or a dataset's text (bytes, str or a one-element array of them)."""
    import h5py

    raw = value[()] if isinstance(value, h5py.Dataset) else value
    if isinstance(raw, np.ndarray):
        raw = raw.reshape(-1)[0] if raw.size else b""
    return raw.decode("utf-8", "replace") if isinstance(raw, bytes) else str(raw)


def _matlab_variable(item: Any) -> np.ndarray | None:
    import h5py

    if not isinstance(item, h5py.Dataset):
        return None
    cls = _text(item.attrs.get("MATLAB_class", b""))
    if cls == "char":  # uint16 code units: the text, e.g. our `units` line
        codes = np.asarray(item[()]).reshape(-1)
        return np.array("".join(chr(int(c)) for c in codes))
    if cls not in NUMERIC_CLASSES or "MATLAB_empty" in item.attrs:
        return None
    data = np.asarray(item[()])
    return _matlab_order(data) if data.dtype.kind in "biuf" else None


def _octave_variable(item: Any) -> np.ndarray | None:
    import h5py

    if not isinstance(item, h5py.Group) or "type" not in item or "value" not in item:
        return None
    kind = _text(item["type"])
    value = item["value"]
    if kind == "string" or kind == "sq_string":
        data = np.asarray(value[()]).reshape(-1)
        return np.array("".join(chr(int(c)) for c in data if int(c)))
    if kind not in OCTAVE_NUMERIC or not isinstance(value, h5py.Dataset):
        return None
    data = np.asarray(value[()])
    return _matlab_order(data) if data.dtype.kind in "biuf" else None


def load(path: Path) -> dict[str, np.ndarray]:
    """Every readable variable of an HDF5 .mat file by name (a FormatError-free best effort:
    the caller says what is missing)."""
    import h5py

    with path.open("rb") as f:
        matlab = f.read(len(MATLAB_73)) == MATLAB_73
    found: dict[str, np.ndarray] = {}
    with h5py.File(path, "r") as h5:
        for name, item in h5.items():
            if name.startswith("#"):  # MATLAB's #refs# and #subsystem# groups
                continue
            value = _matlab_variable(item) if matlab else _octave_variable(item)
            if value is None and not matlab:
                value = _matlab_variable(item)  # an HDF5 file another tool wrote Matlab-style
            if value is not None:
                found[name] = value
    return found
