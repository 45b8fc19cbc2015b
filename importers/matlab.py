"""Named-array files: Matlab .mat (v4 to v7 through scipy.io; v7.3 and Octave `-hdf5` through
h5py; Octave's default text format) and NumPy .npz: a vector and its rate, or named layers.

We write `rate`, `time` (or `angle_deg`, in degrees, on a position project: `rate` is then per
degree) and one column vector per layer (a tile's samples are called `value`), so in Matlab
`plot(time, drive)` works; a project's layers add `units`, the units line of importers/_units.py,
so an import puts each layer back on a track of its kind at its values. A user edits the vectors
and saves with any of Matlab's or Octave's formats.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import scipy.io

from importers import _mat_hdf5, _mat_octave_text, _units
from importers._columns import (
    AXIS_NAMES,
    RATE_NAMES,
    finite_values,
    placed_tile,
    positive_rate,
    rate_from_axis,
)
from timeline.files import crash_isolation
from timeline.plugins.file_formats import FormatError, Imported, Layers, Progress
from timeline.tiles import Tile

PREFERRED = ("value", "data", "drive")


def _load(path: Path) -> dict[str, Any]:
    """The file's variables, parsed in a child process (a damaged file can crash scipy or HDF5)."""
    if path.suffix.lower() == ".npz":
        return _load_npz(path)
    return crash_isolation.run(_parse, path, what=path.name)


def _load_npz(path: Path) -> dict[str, Any]:
    try:
        with np.load(path, allow_pickle=False) as archive:
            return {k: archive[k] for k in archive.files}
    except (OSError, ValueError, EOFError) as exc:
        detail = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
        raise FormatError(f"{path.name} is not a readable .npz file ({detail[:120]})") from None


def _parse(path: Path) -> dict[str, Any]:
    with path.open("rb") as f:
        head = f.read(1024)
    if _mat_hdf5.is_hdf5(head):
        try:
            return _mat_hdf5.load(path)
        except OSError as exc:
            raise FormatError(f"{path.name} is not a readable HDF5 .mat file ({exc})") from None
    if head.startswith(_mat_hdf5.MATLAB_73):
        raise FormatError(f"{path.name} says it is a Matlab v7.3 file but holds no HDF5 data")
    if _mat_octave_text.is_octave_text(head):
        return _mat_octave_text.load(path)
    try:
        contents = scipy.io.loadmat(path, squeeze_me=False, mat_dtype=False)
    except Exception as exc:  # scipy's parser raises many types on malformed input
        raise FormatError(f"{path.name} is not a readable .mat file ({_why(exc)})") from None
    return {k: v for k, v in contents.items() if not k.startswith("__")}


def _why(exc: Exception) -> str:
    """scipy's reason a .mat file cannot be read, in the file's terms where it speaks of code
    ("index out of range", "cannot reshape array of size 8 into shape (...)")."""
    text = str(exc).splitlines()[0] if str(exc) else ""
    if isinstance(exc, LookupError | AttributeError | TypeError) or not text:
        return "its data ends early or is damaged"
    if "could not read bytes" in text:
        return "its data ends early"
    if "reshape" in text:
        return "an array's declared shape does not match the values it holds"
    return text[:120]


def _numeric_vector(value: Any) -> np.ndarray | None:
    """A real numeric vector (1xN, Nx1 or N) as float64, else None."""
    if not isinstance(value, np.ndarray) or value.dtype.kind not in "biuf":
        return None
    if value.ndim > 2 or (value.ndim == 2 and min(value.shape) > 1) or value.size == 0:
        return None
    return value.astype(np.float64).reshape(-1)


class MatlabFormat:
    """Matlab .mat: a tile from one vector; layers written as named vectors with time and rate."""

    name = "mat"
    extensions = (".mat", ".npz")
    reads = "tile"
    writes = "layers"
    options = ("column", "rate")

    def read(
        self,
        path: Path,
        *,
        progress: Progress | None = None,
        column: str | None = None,
        rate: float | None = None,
        **options: Any,
    ) -> Tile | Imported:
        """Read the chosen (or first value-like) vector as a tile, with the file's rate or time."""
        path = Path(path)
        variables = _load(path)
        units = _units_of(variables)
        name = self._choose(variables, column, path.name, units)
        values = finite_values(_numeric_vector(variables[name]), f"{name} in {path.name}")
        file_rate, start = self._rate(variables, len(values), path.name)
        if units is not None and units.rate is not None:
            file_rate = units.rate  # exact: a per-degree rate is a rounded one
        chosen = file_rate or rate
        if chosen is None:
            raise FormatError(f"{path.name} has no rate or time variable: give its rate")
        if progress is not None:
            progress(1.0)
        if units is not None and name in units.kinds:
            names = [name] if column is not None else [k for k in variables if k in units.kinds]
            columns = [(k, finite_values(_numeric_vector(variables[k]), f"{k} in {path.name}"))
                       for k in names]  # fmt: skip
            return _units.kind_placements(columns, units, chosen, start, path.stem, str(path))
        tile = placed_tile(values, chosen, start, f"{path.stem} {name}", str(path))
        return _units.as_shape(tile, path.name)

    @staticmethod
    def _choose(
        variables: dict[str, Any], column: str | None, filename: str, units: _units.Units | None
    ) -> str:
        vectors = [k for k, v in variables.items() if _numeric_vector(v) is not None]
        if column is not None:
            if column not in variables:
                raise FormatError(
                    f"{filename} has no variable {column!r} "
                    f"(it has {', '.join(variables) or 'none'})"
                )
            if column not in vectors:
                raise FormatError(f"{column} in {filename} is not a real numeric vector")
            return column
        values = [k for k in vectors if k.lower() not in AXIS_NAMES + RATE_NAMES]
        if units is not None and any(k in units.kinds for k in values):
            return next(k for k in values if k in units.kinds)
        for k in PREFERRED:
            if k in values:
                return k
        if not values:
            raise FormatError(f"{filename} holds no numeric vector to import")
        return values[0]

    @staticmethod
    def _rate(variables: dict[str, Any], n: int, filename: str) -> tuple[float | None, float]:
        """The rate and start from a rate variable or a time vector (None when neither exists)."""
        lowered = {k.lower(): k for k in variables}
        rate = None
        for key in RATE_NAMES:
            if key in lowered:
                scalar = np.asarray(variables[lowered[key]])
                if scalar.size != 1 or scalar.dtype.kind not in "biuf":
                    raise FormatError(f"{lowered[key]} in {filename} is not a single number")
                rate = positive_rate(scalar.reshape(-1)[0], filename)
                break
        for key in AXIS_NAMES:
            axis = _numeric_vector(variables.get(lowered.get(key, "")))
            if axis is not None and len(axis) == n:
                axis = finite_values(axis, f"{key} in {filename}")
                if rate is None and n > 1:
                    rate = rate_from_axis(axis, filename)
                if key == _units.ANGLE_DEG:  # degrees in the file, radians on the timeline
                    per_rad = None if rate is None else rate * 180.0 / np.pi
                    return per_rad, float(np.radians(axis[0]))
                return rate, float(axis[0])
        return rate, 0.0

    def write(self, source: Layers, path: Path, **options: Any) -> None:
        """Column vectors per layer, plus `time` (or `angle_deg`), `rate` and, for a project's
        layers, `units`: a compressed v5 .mat file, or a .npz archive."""
        n = source.length
        axis = _units.axis_values(source.axis, source.start, source.rate, n)
        arrays: dict[str, Any] = {
            _units.axis_column(source.axis): axis.reshape(-1, 1),
            "rate": np.float64(_units.file_rate(source.axis, source.rate)),
        }
        for key, col in source.columns.items():
            full = np.zeros(n)
            full[: len(col)] = col
            arrays[key] = full.reshape(-1, 1)
        units = _units.describe(list(source.columns), source.axis, source.rate)
        if units is not None:
            arrays["units"] = np.array(units)
        if Path(path).suffix.lower() == ".npz":
            with open(path, "wb") as f:
                np.savez(f, **{k: np.asarray(v).reshape(-1) if np.ndim(v) == 2 else v
                               for k, v in arrays.items()})  # fmt: skip
            return
        scipy.io.savemat(Path(path), arrays, do_compression=True, oned_as="column")


def _units_of(variables: dict[str, Any]) -> _units.Units | None:
    """The units line a `units` text variable holds, if any."""
    value = variables.get("units")
    if not isinstance(value, np.ndarray) or value.dtype.kind not in "US":
        return None
    text = "".join(str(v) for v in value.reshape(-1))
    return _units.parse(text)


FORMAT = MatlabFormat()
