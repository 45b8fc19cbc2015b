"""Helpers shared by the table readers (CSV/TXT and .mat): rates, checks, the placed tile."""

from __future__ import annotations

import math

import numpy as np

from timeline.plugins.file_formats import FormatError, Imported, Placement
from timeline.tiles import SampledTile, Tile

AXIS_NAMES = ("time", "t", "time_s", "seconds", "angle", "angle_deg", "theta", "position")
RATE_NAMES = ("rate", "fs", "sample_rate", "samplerate", "sr")
UNIFORM_TOLERANCE = 1e-6  # relative spread allowed in a time column's steps


def shortest_rate(rate: float, tolerance: float) -> float:
    """The number with fewest digits within tolerance of rate (44100, not 44100.0000001)."""
    for digits in range(1, 18):
        candidate = float(f"{rate:.{digits}g}")
        if abs(candidate - rate) <= tolerance:
            return candidate
    return rate


def rate_from_axis(axis: np.ndarray, name: str) -> float:
    """The sample rate of an evenly spaced, increasing time (or angle) column."""
    if len(axis) < 2:
        raise FormatError(f"{name} has a single row, so its rate is unknown: give the rate")
    steps = np.diff(axis)
    span = float(axis[-1] - axis[0])
    if not (span > 0 and math.isfinite(span)):
        raise FormatError(f"the time column of {name} does not increase")
    step = span / (len(axis) - 1)
    if np.abs(steps - step).max() > UNIFORM_TOLERANCE * step:
        raise FormatError(f"the time column of {name} is not evenly spaced")
    rate = (len(axis) - 1) / span
    # Times written with 17 digits give the rate to a few ulps; snap to the short number it was.
    return shortest_rate(rate, 8 * np.spacing(rate) * len(axis) ** 0.5)


def finite_values(values: np.ndarray, name: str) -> np.ndarray:
    """The values as float64, or a FormatError naming the first non-finite one."""
    values = np.asarray(values, dtype=np.float64).reshape(-1)
    if values.size == 0:
        raise FormatError(f"{name} holds no values")
    bad = ~np.isfinite(values)
    if bad.any():
        raise FormatError(
            f"value {int(np.flatnonzero(bad)[0]) + 1} in {name} is not a finite number"
        )
    return values


def positive_rate(rate: object, name: str) -> float:
    """A rate given in a file or an option, checked to be a positive finite number."""
    try:
        value = float(rate)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        shown = f" ({rate[:40]!r})" if isinstance(rate, str) else ""
        raise FormatError(f"the rate in {name} is not a number{shown}") from None
    if not (math.isfinite(value) and value > 0):
        raise FormatError(f"the rate in {name} must be a positive number, not {value}")
    return value


def placed_tile(
    values: np.ndarray, rate: float, start: float, title: str, source: str
) -> Tile | Imported:
    """A sampled tile, placed at `start` when the time column does not begin at zero."""
    tile = SampledTile(values, rate, title, source)
    if start == 0.0:
        return tile
    return Imported((Placement(tile, start=float(start)),))
