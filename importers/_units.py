"""The units line our rendered files carry, and the placements it gives back on import.

A file of rendered layers (CSV/TXT comment, .mat/.npz `units` variable, WAV comment chunk) says

    haptic-timeline units: time=s drive=N*m stiffness=N*m/rad rate=10000.0/s

the axis column and its unit (`time` in s, or `angle_deg` in degrees on a position project),
each column's layer kind and SI unit, and the exact rate (samples per s, or per degree with the
per-radian number the project keeps). Importing such a file puts each column back on a track of
its kind at the values written; a file without the line is a unitless shape (1 = the track's
full scale), and a table's import says so (a recording's samples are a shape by nature).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from timeline.errors import PluginError
from timeline.plugins.file_formats import Imported, Placement
from timeline.plugins.track_kinds import TrackKind, track_kind
from timeline.tiles import SampledTile, Tile

PREFIX = "haptic-timeline units:"
ANGLE_DEG = "angle_deg"  # the position axis column: degrees (older files: `angle` in radians)
_TOKEN = re.compile(r"(\S+?)=(\S+)")


@dataclass(frozen=True)
class Units:
    """What a units line says: the axis, each column's kind, the exact rate per s or per rad."""

    axis: str  # "time" or "position"
    kinds: dict[str, str]  # column name -> kind id
    rate: float | None  # samples per second or per radian


def _kind(name: str) -> TrackKind | None:
    try:
        return track_kind(name)
    except PluginError:
        return None


def axis_column(axis: str) -> str:
    """The axis column's name: `time` (s) or `angle_deg` (degrees)."""
    return "time" if axis == "time" else ANGLE_DEG


def axis_values(axis: str, start: float, rate: float, n: int) -> np.ndarray:
    """The axis column as written: seconds, or degrees on a position project."""
    values = start + np.arange(n) / rate
    return values if axis == "time" else np.degrees(values)


def file_rate(axis: str, rate: float) -> float:
    """The rate a person reads beside the axis column: per second, or per degree."""
    return rate if axis == "time" else rate * math.pi / 180.0


def describe(columns: list[str], axis: str, rate: float) -> str | None:
    """The units line for these columns, or None when one is not a layer kind (a tile's shape)."""
    kinds = [_kind(name) for name in columns]
    if not columns or any(k is None for k in kinds):
        return None
    tokens = [f"{axis_column(axis)}={'s' if axis == 'time' else 'deg'}"]
    tokens += [f"{k.id}={k.si_unit}" for k in kinds if k is not None]
    if axis == "time":
        tokens.append(f"rate={rate!r}/s")
    else:
        tokens.append(f"rate={file_rate(axis, rate)!r}/deg rate_rad={rate!r}/rad")
    return f"{PREFIX} {' '.join(tokens)}"


def parse(text: str) -> Units | None:
    """The units line in `text` (anywhere in it), or None when there is none."""
    at = text.find(PREFIX)
    if at < 0:
        return None
    line = text[at + len(PREFIX) :].splitlines()[0]
    axis = "time"
    kinds: dict[str, str] = {}
    rate: float | None = None
    for key, value in _TOKEN.findall(line):
        number = value.split("/")[0]
        if key == ANGLE_DEG:
            axis = "position"
        elif key == "rate" and value.endswith("/s") or key == "rate_rad":
            rate = _number(number)
        else:
            kind = _kind(key)
            if kind is not None and kind.si_unit == value:
                kinds[key] = kind.id
    return Units(axis, kinds, rate)


def _number(text: str) -> float | None:
    try:
        value = float(text)
    except ValueError:
        return None
    return value if math.isfinite(value) and value > 0 else None


def unit_gain(kind: TrackKind) -> float:
    """The clip gain that plays a tile of SI values at those values on a new track of the kind:
    1/full scale, nudged by an ulp when that makes gain * full scale exactly 1."""
    gain = 1.0 / kind.full_scale
    for candidate in (gain, math.nextafter(gain, math.inf), math.nextafter(gain, 0.0)):
        if candidate * kind.full_scale == 1.0:
            return candidate
    return gain


def kind_placements(
    columns: list[tuple[str, np.ndarray]],
    units: Units,
    rate: float,
    start: float,
    stem: str,
    source: str,
) -> Imported:
    """Each column on a track of its kind, at the values written (SI)."""
    placements = []
    for name, values in columns:
        kind = track_kind(units.kinds[name])
        tile = SampledTile(values, rate, f"{stem} {name}", source)
        clip = {"gain": unit_gain(kind)}
        placements.append(Placement(tile, start=float(start), kind=kind.id, clip=clip))
    said = ", ".join(f"{name} in {track_kind(units.kinds[name]).si_unit}" for name, _ in columns)
    axis = "a time project's" if units.axis == "time" else "a position project's"
    note = (
        f"{Path(source).name} holds {axis} layers ({said}): placed on tracks of those kinds at "
        "those values"
    )
    return Imported(tuple(placements), notes=(note,))


def shape_note(filename: str) -> str:
    """The note for a table that does not say what its numbers are."""
    return (
        f"{filename} does not say its layer kind or unit (no '{PREFIX}' line): its values are "
        "read as a unitless shape, 1 = the track's full scale"
    )


def as_shape(result: Tile | Imported, filename: str) -> Imported:
    """A table's tile (or placed tile) with the note that it is a shape."""
    placed = result if isinstance(result, Imported) else Imported((Placement(result),))
    return Imported(placed.placements, placed.tracks, (*placed.notes, shape_note(filename)))
