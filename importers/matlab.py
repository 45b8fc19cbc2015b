"""Matlab .mat files (v4 to v7) through scipy.io: a vector and its rate, or named layers and time.

We write `rate`, `time` and one column vector per layer (a tile's samples are called `value`),
so in Matlab `plot(time, drive)` works; a user edits the vectors and saves with `save(..., '-v7')`.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import scipy.io

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
    """The file's variables, parsed in a child process (a damaged file can crash scipy)."""
    with path.open("rb") as f:
        if f.read(128)[:19] == b"MATLAB 7.3 MAT-file":
            raise FormatError(f"{path.name} is a Matlab v7.3 (HDF5) file: save it with -v7")
    return crash_isolation.run(_parse, path, what=path.name)


def _parse(path: Path) -> dict[str, Any]:
    try:
        contents = scipy.io.loadmat(path, squeeze_me=False, mat_dtype=False)
    except Exception as exc:  # scipy's parser raises many types on malformed input
        detail = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
        raise FormatError(f"{path.name} is not a readable .mat file ({detail[:120]})") from None
    return {k: v for k, v in contents.items() if not k.startswith("__")}


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
    extensions = (".mat",)
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
        name = self._choose(variables, column, path.name)
        values = finite_values(_numeric_vector(variables[name]), f"{name} in {path.name}")
        file_rate, start = self._rate(variables, len(values), path.name)
        chosen = file_rate or rate
        if chosen is None:
            raise FormatError(f"{path.name} has no rate or time variable: give its rate")
        if progress is not None:
            progress(1.0)
        return placed_tile(values, chosen, start, f"{path.stem} {name}", str(path))

    @staticmethod
    def _choose(variables: dict[str, Any], column: str | None, filename: str) -> str:
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
                return rate, float(axis[0])
        return rate, 0.0

    def write(self, source: Layers, path: Path, **options: Any) -> None:
        """Column vectors per layer, plus `time` (or `angle`) and `rate`, in a v5 .mat file."""
        axis_name = "time" if source.axis == "time" else "angle"
        n = source.length
        arrays: dict[str, Any] = {
            axis_name: (source.start + np.arange(n) / source.rate).reshape(-1, 1),
            "rate": np.float64(source.rate),
        }
        for key, col in source.columns.items():
            full = np.zeros(n)
            full[: len(col)] = col
            arrays[key] = full.reshape(-1, 1)
        scipy.io.savemat(Path(path), arrays, do_compression=True, oned_as="column")


FORMAT = MatlabFormat()
