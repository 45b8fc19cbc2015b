"""Turn a project into what a device plays: coefficient blocks (time) or tables (position)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from timeline.errors import DeviceError
from timeline.model import Project
from timeline.plugins.device_protocol import (
    CoefficientBlock,
    DeviceInfo,
    Hand,
    PositionProgram,
    PositionTable,
    Program,
)
from timeline.plugins.track_kinds import track_kind
from timeline.rendering.mixer import render

BLOCK_SECONDS = 0.1  # length of one coefficient block
DEFAULT_POSITION_SECONDS = 2.0  # how long a position program plays unless the hand turns through it


@dataclass(frozen=True, eq=False)
class Playback:
    """A program ready for a device, with its length and the layer names for telemetry columns.

    `layer_names` maps a telemetry layer key (d, k, b, m) to the kind id the project uses.
    """

    program: Program
    duration: float
    layer_names: dict[str, str]


def layer_terms(layers: dict[str, np.ndarray]) -> tuple[dict[str, np.ndarray], dict[str, str]]:
    """Sum rendered layers by the torque-law term their kind feeds (d, k, b or m)."""
    sums: dict[str, np.ndarray] = {}
    names: dict[str, str] = {}
    for kind_id, values in layers.items():
        term = track_kind(kind_id).term
        values = np.asarray(values, dtype=np.float64)
        sums[term] = sums[term] + values if term in sums else values.copy()
        names[term] = kind_id if term not in names else f"{names[term]}+{kind_id}"
    return sums, {t: names[t] for t in "dkbm" if t in names}


def coefficient_blocks(
    project: Project,
    rate: float,
    duration: float | None = None,
    quality: str = "normal",
    block_seconds: float = BLOCK_SECONDS,
) -> tuple[list[CoefficientBlock], dict[str, str]]:
    """Render a time project at a device rate into blocks of d, k, b (and m if a mass layer exists).

    Absent layers are zero (mass: None). Returns the blocks and the layer names (term -> kind).
    """
    if project.axis != "time":
        raise DeviceError("coefficient blocks come from a time project; use position_program")
    duration = project.duration if duration is None else float(duration)
    if not math.isfinite(duration) or duration <= 0:
        raise DeviceError(f"nothing to play: the duration is {duration:g} s")
    sums, names = layer_terms(render(project, 0.0, duration, rate, quality))
    n = int(round(duration * rate))
    zero = np.zeros(n)
    d, k, b = (sums.get(t, zero) for t in "dkb")
    m = sums.get("m")
    size = max(1, int(round(block_seconds * rate)))
    return CoefficientBlock.split(d, k, b, m, size), names


def position_table(
    project: Project, quality: str = "normal"
) -> tuple[PositionTable, dict[str, str]]:
    """Render a position project into tables over its angle range (T, B, M)."""
    if project.axis != "position":
        raise DeviceError("position tables come from a position project; use coefficient_blocks")
    clips = [c for t in project.tracks for c in t.clips]
    if not clips:
        raise DeviceError("nothing to play: the project has no clips")
    start = min(0.0, min(c.start for c in clips))
    stop = project.duration
    sums, names = layer_terms(render(project, start, stop, project.rate, quality))
    n = int(round((stop - start) * project.rate))
    torque = sums.get("d", np.zeros(n))
    table = PositionTable(start, project.rate, torque, sums.get("b"), sums.get("m"))
    return table, names


def rest_angles(table: PositionTable) -> np.ndarray:
    """Table angles where T(theta) changes from pushing up to pushing down: stable rest points.

    Runs of (numerical) zeros between the two signs count once, at their middle.
    """
    t = table.torque
    nz = np.flatnonzero(np.abs(t) > 1e-9 * np.abs(t).max(initial=0.0))
    i = np.flatnonzero((t[nz[:-1]] > 0) & (t[nz[1:]] < 0))
    lo, hi = nz[i], nz[i + 1]
    exact = hi - lo == 1
    where = np.where(exact, lo + t[lo] / (t[lo] - t[hi]), (lo + hi) / 2.0)
    return table.start + where / table.rate


def position_program(
    project: Project,
    duration: float | None = None,
    hand: Hand | None = None,
    origin: float | None = None,
    quality: str = "normal",
) -> tuple[PositionProgram, dict[str, str]]:
    """A position program: the tables, where the knob starts and how long it plays.

    The knob starts at `origin` (a table angle, rad), by default the first stable rest point.
    Without a duration it plays long enough for a turning hand to sweep to the table's end (or
    start), otherwise DEFAULT_POSITION_SECONDS.
    """
    table, names = position_table(project, quality)
    if origin is None:
        rests = rest_angles(table)
        origin = float(rests[0]) if rests.size else table.start
    if duration is None:
        speed = hand.turn_speed if hand else 0.0
        if speed:
            span = (table.stop - origin) if speed > 0 else (origin - table.start)
            duration = min(60.0, max(0.5, span / abs(speed)))
        else:
            duration = DEFAULT_POSITION_SECONDS
    return PositionProgram(table, float(duration), float(origin)), names


def prepare(
    project: Project,
    info: DeviceInfo,
    duration: float | None = None,
    hand: Hand | None = None,
    quality: str = "normal",
    origin: float | None = None,
) -> Playback:
    """Everything `play` needs: the program for the project's axis at the device's rate.

    `origin` (rad) only applies to position projects: the table angle where the knob starts.
    """
    if project.axis == "position":
        program, names = position_program(project, duration, hand, origin, quality)
        return Playback(program, program.duration, names)
    blocks, names = coefficient_blocks(project, info.rate, duration, quality)
    return Playback(blocks, sum(len(b) for b in blocks) / info.rate, names)
