"""Apple AHAP (Core Haptics JSON): transient and continuous events, parameter curves.

Reading turns the pattern into one vibration design (timeline.edits.vibration): the felt
amplitude is intensity squared, where intensity = event intensity x Attack/Decay/Release envelope x
HapticIntensityControl (a multiplier, linear between curve points, stepped by dynamic
parameters); sharpness = event sharpness + HapticSharpnessControl, clamped to 0..1. Breakpoints
sit at every event edge, envelope corner and ramp crossing, control point, and where a clamp
starts; between them points are added (evenly in intensity) until the design's straight
amplitude segments are within READ_TOLERANCE of the player's curve. Continuous events cover
[Time, Time + EventDuration), so at a join the later event's value holds; overlapping ones add
(summed from one table of their knots). Controls apply to every event, transients included
(Apple's documentation; docs/formats.md quotes it), so the transients of Apple-made files are
read as played; those of Meta's converter as written (it means them to play apart from its
curves). Audio events are skipped with a note; out-of-range control values are clamped with a
note, as Core Haptics clamps them; event types are matched in any case.

Sharpness follows the tool a file came from. Meta's and Lofelt's converters (the signature:
continuous events of intensity 1 and sharpness 0 shaped by curves) write sharpness =
sqrt(frequency), transients with sharpness = emphasis frequency, and duck the intensity control
point at each emphasis by 20 %; reading such a file undoes the ducking and squares the
sharpness. Other files (Apple's own, hand-made) are read with frequency = sharpness. The
convention is kept with the design, so an export writes the file's numbers back.

Writing: importers.ahap_writer (controls neutral at every transient, no ducking);
importers.ahap_playback evaluates a pattern as Apple documents playing it, for the tests.
"""

from __future__ import annotations

import bisect
import heapq
import math
from pathlib import Path
from typing import Any

import numpy as np

from importers import _vibration as vib
from importers._envelope_fit import squares_of_roots
from importers.ahap_writer import (  # the writer's limits are this format's limits
    MAX_CONTINUOUS,
    MAX_CURVE_POINTS,
    WRITE_TOLERANCE,
    design_pattern,
)
from timeline.analysis.breakpoints import simplify
from timeline.edits.vibration import (
    Emphasis,
    VibrationDesign,
    design_of,
    design_placements,
    sharpness_convention,
)
from timeline.model import Project
from timeline.plugins.file_formats import FormatError, Imported, Progress

MAX_EVENTS = 50_000  # pattern entries read from one file (a bound on time: formats.md)
DEFAULT_INTENSITY = 1.0
DEFAULT_SHARPNESS = 0.5
DUCKING = 0.8  # Meta's converter: intensity control x 0.8 at a point that carries an emphasis
READ_TOLERANCE = 0.005  # amplitude: design vs the player's curve
# The fit is held to its tolerance at the curve's samples; between them a fast attack may stray a
# little further (0.0050025 seen), so breakpoints are fitted with a margin.
FIT_TOLERANCE = 0.9 * READ_TOLERANCE
GRID = 64  # samples per interval between knots where the read curve bends
MAX_LEVELS = 64  # distinct event sharpness values whose clamping points are found exactly
SAME_TIME = 1e-9  # s: a control point this close to a transient is at it (curve times are relative)
CREATED = "haptic-timeline"
LINEAR_NOTE = "sharpness = frequency"
SQRT_NOTE = "sharpness = sqrt(frequency)"
NEUTRAL_NOTE = "controls neutral at transients"  # our files since the writer left ducking out
__all__ = ["MAX_CURVE_POINTS", "WRITE_TOLERANCE", "AhapFormat", "design_pattern", "read_design"]


def _parameters(event: dict[str, Any], where: str, notes: list[str]) -> dict[str, float]:
    found: dict[str, float] = {}
    params = event.get("EventParameters", [])
    if not isinstance(params, list):
        raise FormatError(f"{where}: EventParameters must be a list")
    for p in params:
        if not isinstance(p, dict) or not isinstance(p.get("ParameterID"), str):
            raise FormatError(f"{where}: each event parameter needs a ParameterID")
        pid = p["ParameterID"]
        if pid == "Sustained":
            found[pid] = float(bool(p.get("ParameterValue", True)))
            continue
        if "ParameterValue" not in p:
            raise FormatError(f"{where}: {pid} has no ParameterValue")
        lo = 0.0 if pid.startswith("Haptic") or pid.endswith("Time") else -math.inf
        value = vib.number(p["ParameterValue"], f"{where}: {pid}", lo)
        if pid in ("HapticIntensity", "HapticSharpness") and value > 1.0:
            notes.append(f"{where}: {pid} {value:g} clamped to 1")
            value = 1.0
        found[pid] = value
    return found


def _event(event: Any, where: str, notes: list[str]) -> dict[str, Any] | None:
    if not isinstance(event, dict) or not isinstance(event.get("EventType"), str):
        raise FormatError(f"{where}: an Event needs an EventType")
    kind = HAPTIC_TYPES.get(event["EventType"].lower())
    if kind is None:
        notes.append(f"{event['EventType']} events are not haptic and were skipped")
        return None
    if kind != event["EventType"]:
        notes.append(f"{where}: event type {event['EventType']!r} read as {kind}")
    if "Time" not in event:
        raise FormatError(f"{where}: the event has no Time")
    params = _parameters(event, where, notes)
    out = {
        "type": kind,
        "time": vib.number(event["Time"], f"{where}: Time", 0.0, vib.MAX_DURATION),
        "intensity": params.get("HapticIntensity", DEFAULT_INTENSITY),
        "sharpness": params.get("HapticSharpness", DEFAULT_SHARPNESS),
    }
    if kind == "HapticContinuous":
        if "EventDuration" not in event:
            raise FormatError(f"{where}: the continuous event has no EventDuration")
        out["duration"] = vib.number(
            event["EventDuration"], f"{where}: EventDuration", 0.0, vib.MAX_DURATION
        )
        if out["duration"] > MAX_CONTINUOUS:
            notes.append(f"a continuous event is longer than Core Haptics' {MAX_CONTINUOUS:g} s")
        out["attack"] = params.get("AttackTime", 0.0)
        out["decay"] = params.get("DecayTime", 0.0)
        out["release"] = params.get("ReleaseTime", 0.0)
        out["sustained"] = bool(params.get("Sustained", 1.0))
    return out


HAPTIC_TYPES = {"haptictransient": "HapticTransient", "hapticcontinuous": "HapticContinuous"}


def _control_range(pid: str) -> tuple[float, float] | None:
    return {"HapticIntensityControl": (0.0, 1.0), "HapticSharpnessControl": (-1.0, 1.0)}.get(pid)


def _curve(
    curve: Any, where: str, notes: list[str]
) -> tuple[str, float, list[tuple[float, float]]] | None:
    if not isinstance(curve, dict):
        raise FormatError(f"{where}: a ParameterCurve must be an object")
    pid = curve.get("ParameterID")
    bounds = _control_range(pid) if isinstance(pid, str) else None
    if bounds is None:
        return None  # audio controls and unknown parameters do not touch haptics
    start = vib.number(curve.get("Time"), f"{where}: Time", 0.0, vib.MAX_DURATION)
    points = curve.get("ParameterCurveControlPoints")
    if not isinstance(points, list) or not points:
        raise FormatError(f"{where}: a ParameterCurve needs control points")
    times, values = [], []
    for k, p in enumerate(points):
        if not isinstance(p, dict):
            raise FormatError(f"{where}: each control point must be an object")
        for field in ("Time", "ParameterValue"):
            if field not in p:
                raise FormatError(f"{where}: control point {k + 1} has no {field}")
        times.append(vib.number(p["Time"], f"{where}: control point Time", 0.0))
        values.append(_control_value(p["ParameterValue"], f"{where}: control point", bounds, notes))
    if any(b < a for a, b in zip(times, times[1:], strict=False)):
        raise FormatError(f"{where}: control point times go backwards")
    # Apple's control point times are relative to the curve; Meta's and Lofelt's converters write
    # them absolute (the first equals the curve's Time). Accept both.
    if not (start > 0 and times[0] == start):
        times = [t + start for t in times]
    return pid, times[0], list(zip(times, values, strict=True))


def _control_value(value: Any, where: str, bounds: tuple[float, float], notes: list[str]) -> float:
    """A control value, clamped into its range with a note (Core Haptics clamps out-of-range
    values on load)."""
    number = vib.number(value, f"{where} value")
    if bounds[0] <= number <= bounds[1]:
        return number
    said = f"control values outside {bounds[0]:g} to {bounds[1]:g} were clamped"
    if not any(n.startswith(said) for n in notes):
        notes.append(f"{said}, as Core Haptics does (the first: {number:g} at {where})")
    return min(bounds[1], max(bounds[0], number))


def _dynamic(
    param: Any, where: str, notes: list[str]
) -> tuple[str, float, list[tuple[float, float]]] | None:
    if not isinstance(param, dict):
        raise FormatError(f"{where}: a Parameter must be an object")
    pid = param.get("ParameterID")
    bounds = _control_range(pid) if isinstance(pid, str) else None
    if bounds is None:
        return None
    time = vib.number(param.get("Time"), f"{where}: Time", 0.0, vib.MAX_DURATION)
    return pid, time, [(time, _control_value(param.get("ParameterValue"), where, bounds, notes))]


def _too_many(entries: int, points: int, name: str) -> FormatError:
    if not points:
        return FormatError(
            f"{name} has {entries:,} pattern entries; at most {MAX_EVENTS:,} are read"
        )
    return FormatError(
        f"{name} has {entries:,} pattern entries and {points:,} curve control points; "
        f"at most {MAX_EVENTS:,} in all are read"
    )


def _refuse_long_pattern(text: str, name: str) -> None:
    """Refuse a pattern of more than MAX_EVENTS entries and control points without building it.

    Every pattern entry and control point is a JSON object, and an object opens with a "{" that
    no escape can stand for, so the count of "{" in the text is never below their number
    (braces in strings and other objects only add): at or under the limit, the file is parsed
    as usual. Over it, the text is parsed once with each object dropped as soon as it is read
    (keeping only the length of a "Pattern" list and of each control point list), so the exact
    count costs about the text's size in memory instead of the whole document's objects (8x).
    """
    if text.count("{") <= MAX_EVENTS or not text.lstrip().startswith("{"):
        return  # (a document that is not an object is refused as no AHAP once parsed)
    last: list[Any] = [None]
    points = [0]

    def dropped(pairs: list[tuple[str, Any]]) -> None:
        for key, value in pairs:
            if value.__class__ is list and key == "ParameterCurveControlPoints":
                points[0] += len(value)
        last[0] = pairs  # the document itself is the last object read

    vib.parse_json(text, name, "AHAP", object_pairs_hook=dropped)
    pattern = [v for k, v in last[0] or () if k == "Pattern"]
    entries = len(pattern[-1]) if pattern and isinstance(pattern[-1], list) else 0
    if entries + points[0] > MAX_EVENTS:
        raise _too_many(entries, points[0], name)


def _point_count(pattern: list[Any]) -> int:
    """The control points of the pattern's curves (each counts against MAX_EVENTS)."""
    count = 0
    for entry in pattern:
        curve = entry.get("ParameterCurve") if isinstance(entry, dict) else None
        points = curve.get("ParameterCurveControlPoints") if isinstance(curve, dict) else None
        count += len(points) if isinstance(points, list) else 0
    return count


def _entries(pattern: list[Any], name: str):
    points = _point_count(pattern)
    if len(pattern) + points > MAX_EVENTS:
        raise _too_many(len(pattern), points, name)
    events: list[dict[str, Any]] = []
    controls: list[tuple[str, float, list[tuple[float, float]]]] = []
    notes: list[str] = []
    for k, entry in enumerate(pattern):
        where = f"{name}, pattern entry {k + 1}"
        if not isinstance(entry, dict):
            raise FormatError(f"{where} is not an object")
        if "Event" in entry:
            event = _event(entry["Event"], where, notes)
            if event is not None:
                events.append(event)
        elif "ParameterCurve" in entry:
            control = _curve(entry["ParameterCurve"], where, notes)
            if control is not None:
                controls.append(control)
        elif "Parameter" in entry:
            control = _dynamic(entry["Parameter"], where, notes)
            if control is not None:
                controls.append(control)
        else:
            raise FormatError(f"{where} is not an Event, ParameterCurve or Parameter")
    return events, controls, notes


# --- the player's curves ------------------------------------------------------------------------


class _Control:
    """A control over time: linear between points, stepping where two share a time."""

    def __init__(self, default: float) -> None:
        self._t, self._v = [0.0], [default]
        self.t, self.v = np.array(self._t), np.array(self._v)

    def set_from(self, start: float, points: list[tuple[float, float]]) -> None:
        """From `start` on, follow `points` (a curve, or one point for a dynamic parameter)."""
        if start >= self._t[-1]:
            left = self._v[-1]
        else:  # a curve that starts before the last one ended replaces it from there
            k = bisect.bisect_left(self._t, start)
            left = self._just_before(start, k)
            del self._t[k:], self._v[k:]
        self._t += [start] + [p[0] for p in points]
        self._v += [left] + [p[1] for p in points]

    def _just_before(self, u: float, k: int) -> float:
        """at(u, left=True) for one time u with bisect_left(_t, u) == k, from the two points
        around it (the same operations as at(), so the same bits, without an array of all)."""
        j = max(k - 1, 0)
        nxt = min(j + 1, len(self._t) - 1)
        width = self._t[nxt] - self._t[j]
        slope = (self._v[nxt] - self._v[j]) / width if width > 0 else 0.0
        return self._v[j] + slope * (u - self._t[j])

    def freeze(self) -> _Control:
        self.t, self.v = np.array(self._t), np.array(self._v)
        return self

    def at(self, u: np.ndarray, left: bool = False) -> np.ndarray:
        """Values at times u (the value just before u where `left`); the last value holds."""
        k = np.searchsorted(self.t, u, side="left" if left else "right") - 1
        k = np.clip(k, 0, len(self.t) - 1)
        nxt = np.minimum(k + 1, len(self.t) - 1)
        width = self.t[nxt] - self.t[k]
        safe = np.where(width > 0, width, 1.0)
        slope = np.where(width > 0, (self.v[nxt] - self.v[k]) / safe, 0.0)
        return self.v[k] + slope * (np.asarray(u) - self.t[k])


def _adsr(local: np.ndarray, e: dict[str, np.ndarray]) -> np.ndarray:
    """Core Haptics' continuous-event envelope: linear attack, decay (unsustained), release."""
    with np.errstate(divide="ignore", invalid="ignore"):
        env = np.where(e["attack"] > 0, local / e["attack"], 1.0)
        decay = np.clip(1.0 - (local - e["attack"]) / e["decay"], 0.0, 1.0)
        env = np.minimum(env, np.where(~e["sustained"] & (e["decay"] > 0), decay, 1.0))
        release = np.clip((e["duration"] - local) / e["release"], 0.0, 1.0)
        env = np.minimum(env, np.where(e["release"] > 0, release, 1.0))
    return np.clip(env, 0.0, 1.0)


FIELDS = ("time", "duration", "intensity", "sharpness", "attack", "decay", "release", "sustained")


class _Player:
    """Intensity and sharpness of the continuous events at any time, as Core Haptics plays them."""

    def __init__(self, events: list[dict[str, Any]], intensity, sharpness) -> None:
        events = sorted(events, key=lambda e: e["time"])
        self.e = {f: np.array([e[f] for e in events]) for f in FIELDS}
        self.end = self.e["time"] + self.e["duration"]
        self.disjoint = bool(np.all(self.e["time"][1:] >= self.end[:-1]))
        self.intensity, self.sharpness = intensity.freeze(), sharpness.freeze()
        self._sum: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None
        self._owner: tuple[np.ndarray, np.ndarray] = (np.zeros(0), np.zeros(0, dtype=np.int64))

    def values(
        self, u: np.ndarray, left: bool = False, clip: bool = True
    ) -> tuple[np.ndarray, np.ndarray]:
        """Intensity and sharpness at times u (just before u where `left`), clamped to 0..1 as
        the player clamps them unless not `clip`."""
        if self.disjoint:
            level, sharp = self._one_at_a_time(u, left)
        else:
            level, sharp = self._overlapping(u, left)
        level = level * self.intensity.at(u, left)
        sharp = sharp + self.sharpness.at(u, left)
        if not clip:
            return level, sharp
        return np.clip(level, 0.0, 1.0), np.clip(sharp, 0.0, 1.0)

    @staticmethod
    def _inside(u: np.ndarray, start: np.ndarray, end: np.ndarray, left: bool) -> np.ndarray:
        """Whether u is in [start, end) (in (start, end] for values just before u)."""
        if left:
            return (u > start) & (u <= end)
        return (u >= start) & (u < end)

    def _one_at_a_time(self, u: np.ndarray, left: bool):
        k = np.searchsorted(self.e["time"], u, side="left" if left else "right") - 1
        kk = np.clip(k, 0, len(self.end) - 1)
        e = {f: v[kk] for f, v in self.e.items()}
        local = u - e["time"]
        inside = (k >= 0) & self._inside(u, e["time"], self.end[kk], left)
        level = np.where(inside, e["intensity"] * _adsr(local, e), 0.0)
        return level, np.where(inside, e["sharpness"], 0.0)

    def _overlapping(self, u: np.ndarray, left: bool):
        """The events' envelopes summed, and the sharpness of the latest-starting event playing,
        from piecewise tables built once (near-linear in the events, not events x samples)."""
        if self._sum is None:
            self._sum = _summed_envelopes(self.e)
            self._owner = _latest_playing(self.e["time"], self.end)
        x, value, slope = self._sum
        side = "left" if left else "right"
        k = np.searchsorted(x, u, side=side) - 1
        kk = np.clip(k, 0, len(x) - 1)
        level = np.where(k >= 0, value[kk] + slope[kk] * (u - x[kk]), 0.0)
        bounds, owner = self._owner
        j = np.clip(np.searchsorted(bounds, u, side=side) - 1, 0, len(owner) - 1)
        playing = (np.searchsorted(bounds, u, side=side) > 0) & (owner[j] >= 0)
        sharp = np.where(playing, self.e["sharpness"][np.maximum(owner[j], 0)], 0.0)
        return np.maximum(level, 0.0), sharp


def _envelope_table(e: dict[str, np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    """Each event's envelope x intensity as knots (local times, values), one row per event:
    every corner and every crossing of two ramps, so it is linear between knots."""
    a, dcy, rel, d = e["attack"], e["decay"], e["release"], e["duration"]
    with np.errstate(divide="ignore", invalid="ignore"):
        up_down = np.where((a > 0) & (rel > 0), d * a / (a + rel), 0.0)
        # decay 1 - (x - a) / dcy meets release (d - x) / rel
        meet = np.where(
            (dcy > 0) & (rel > 0) & (rel != dcy), (rel * (1 + a / dcy) - d) / (rel / dcy - 1), 0.0
        )
    decayed = np.where(e["sustained"], 0.0, a + dcy)
    x = np.stack([np.zeros_like(d), a, decayed, d - rel, d, up_down, meet], axis=1)
    x = np.sort(np.clip(np.nan_to_num(x), 0.0, d[:, None]), axis=1)
    rows = {f: v[:, None] for f, v in e.items()}
    return x, e["intensity"][:, None] * _adsr(x, rows)


def _summed_envelopes(e: dict[str, np.ndarray]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The sum of all events' envelopes as sorted knots with the value and slope just after each
    (each event is zero outside [start, end))."""
    x, y = _envelope_table(e)
    width = np.diff(x, axis=1)
    slope = np.where(width > 0, np.diff(y, axis=1) / np.where(width > 0, width, 1.0), 0.0)
    zeros = np.zeros((len(x), 1))
    slope_in, slope_out = np.hstack([zeros, slope]), np.hstack([slope, zeros])
    arriving = np.hstack([zeros, y[:, :-1] + slope * width])
    leaving = np.hstack([y[:, :-1], zeros])
    at = (e["time"][:, None] + x).ravel()
    order = np.argsort(at, kind="stable")
    at = at[order]
    jump = (leaving - arriving).ravel()[order]
    after = np.cumsum((slope_out - slope_in).ravel()[order])
    value = np.cumsum(jump) + np.concatenate([[0.0], np.cumsum(after[:-1] * np.diff(at))])
    value[np.abs(value) < 1e-12] = 0.0
    return at, value, after


def _latest_playing(start: np.ndarray, end: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Times where the latest-starting playing event can change, and its index from each on
    (-1: none); events sorted by start. One sweep with a heap: O(n log n)."""
    bounds = np.unique(np.concatenate([start, end]))
    owner = np.full(len(bounds), -1, dtype=np.int64)
    heap: list[int] = []
    i = 0
    for j, b in enumerate(bounds.tolist()):
        while i < len(start) and start[i] <= b:
            heapq.heappush(heap, -i)
            i += 1
        while heap and end[-heap[0]] <= b:
            heapq.heappop(heap)
        owner[j] = -heap[0] if heap else -1
    return bounds, owner


def _clip_crossings(player: _Player) -> np.ndarray:
    """Times where event sharpness + sharpness control crosses 0 or 1 (the player clamps there,
    so the read curve needs a knot), for up to MAX_LEVELS distinct event sharpness values."""
    levels = np.unique(player.e["sharpness"])[:MAX_LEVELS]
    t, v = player.sharpness.t, player.sharpness.v
    targets = np.concatenate([-levels, 1.0 - levels])[None, :]
    v0, v1 = v[:-1, None], v[1:, None]
    with np.errstate(divide="ignore", invalid="ignore"):
        frac = np.where(v1 != v0, (targets - v0) / (v1 - v0), -1.0)
    cross = (frac > 0) & (frac < 1)
    return (t[:-1, None] + np.where(cross, frac, 0.0) * (t[1:, None] - t[:-1, None]))[cross]


def _knots(player: _Player, controls) -> np.ndarray:
    corners = player.e["time"][:, None] + _envelope_table(player.e)[0]
    times = [corners.ravel(), _clip_crossings(player)]
    times += [np.array([t for t, _ in pts]) for _, _, pts in controls]
    knots = np.unique(np.concatenate(times))
    knots = knots[(knots >= player.e["time"].min()) & (knots <= player.end.max())]
    if player.disjoint:
        return knots
    return np.unique(np.concatenate([knots, _level_crossings(player, knots)]))


def _level_crossings(player: _Player, knots: np.ndarray) -> np.ndarray:
    """Where overlapping events' summed intensity x control crosses 1 (the player clamps it
    there): between knots both factors are straight, so their product meets 1 at a root of a
    quadratic."""
    if len(knots) < 2:
        return knots[:0]
    la = player.values(knots[:-1], clip=False)[0]
    lb = player.values(knots[1:], left=True, clip=False)[0]
    ca = player.intensity.at(knots[:-1])
    cb = player.intensity.at(knots[1:], left=True)
    with np.errstate(divide="ignore", invalid="ignore"):
        ea, eb = la / np.where(ca > 0, ca, 1.0), lb / np.where(cb > 0, cb, 1.0)
        a, b, c = (eb - ea) * (cb - ca), ea * (cb - ca) + ca * (eb - ea), ea * ca - 1.0
        root = np.sqrt(np.maximum(b * b - 4 * a * c, 0.0))
        found = []
        for tau in ((-b + root) / (2 * a), (-b - root) / (2 * a), -c / b):
            found.append(np.where(np.isfinite(tau) & (tau > 0) & (tau < 1), tau, np.nan))
    taus = np.stack(found)
    crossing = (la - 1.0) * (lb - 1.0) < 0
    times = knots[:-1] + taus * np.diff(knots)
    return times[:, crossing][np.isfinite(times[:, crossing])]


def _stepped(knots: np.ndarray, player: _Player, which: int) -> tuple[np.ndarray, np.ndarray]:
    """(time, value) at every knot, two where the value jumps (left then right)."""
    right = player.values(knots)[which].copy()
    left = player.values(knots, left=True)[which]
    right[-1] = left[-1]  # the design ends with the events' last value
    jump = np.abs(left - right) > 1e-12
    jump[0] = False
    counts = 1 + jump.astype(np.int64)
    t = np.repeat(knots, counts)
    v = np.empty(len(t))
    at_right = np.cumsum(counts) - 1
    v[at_right] = right
    v[at_right[jump] - 1] = left[jump]
    return t, v


def _squared(knots: np.ndarray, player: _Player, which: int, tolerance: float):
    """The player's curve squared, as breakpoints within tolerance of it."""
    t, r = _stepped(knots, player, which)
    tt, vv = squares_of_roots(t, r, tolerance)
    mid = 0.5 * (knots[:-1] + knots[1:])
    chord = 0.5 * (player.values(knots)[which][:-1] + player.values(knots, left=True)[which][1:])
    if not np.any(np.abs(player.values(mid)[which] - chord) > 1e-9):
        if player.disjoint:
            return tt, vv
        # overlapping events leave many knots on straight stretches (a sum clamped at 1)
        points = simplify(tt, vv, 1e-9)
        return np.array([p[0] for p in points]), np.array([p[1] for p in points])
    # Overlapping events or an envelope times a control bend the curve between knots: add the
    # squared curve's own samples and reduce them within the tolerance.
    # (the knots' own values are exact, both sides of a step; points between knots from the
    # straight-root assumption are not, so they are left out)
    inner = np.arange(1, GRID) / GRID  # GRID samples in every interval between knots
    u = (knots[:-1, None] + np.diff(knots)[:, None] * inner[None, :]).ravel()
    grid = np.concatenate([t, u])
    values = np.concatenate([r * r, player.values(u)[which] ** 2])
    order = np.argsort(grid, kind="stable")
    points = simplify(grid[order], values[order], tolerance)
    return np.array([p[0] for p in points]), np.array([p[1] for p in points])


def _converter_made(events, controls) -> bool:
    """Made by Meta's or Lofelt's converter: flat continuous events shaped by control curves."""
    continuous = [e for e in events if e["type"] == "HapticContinuous"]
    return (
        bool(continuous)
        and all(e["intensity"] == 1.0 and e["sharpness"] == 0.0 for e in continuous)
        and any(pid == "HapticIntensityControl" for pid, _, _ in controls)
    )


def _convention(doc: dict[str, Any], events, controls) -> str:
    meta = doc.get("Metadata")
    if isinstance(meta, dict) and meta.get("Created") == CREATED:
        return "linear" if str(meta.get("Description")).startswith(LINEAR_NOTE) else "sqrt"
    return "sqrt" if _converter_made(events, controls) else "linear"


def _neutral(doc: dict[str, Any]) -> bool:
    """Written by this writer since it left ducking out (controls neutral at transients)."""
    meta = doc.get("Metadata")
    return isinstance(meta, dict) and meta.get("Layout") == NEUTRAL_NOTE


def _pairs(t: np.ndarray, v: np.ndarray) -> list[tuple[float, float]]:
    return list(zip(t.tolist(), v.tolist(), strict=True))


def _unducked(points: list[tuple[float, float]], marks: np.ndarray) -> list[tuple[float, float]]:
    """Control points with the first at each emphasis time (`marks`, sorted once by the caller
    for all curves) raised back by 1 / DUCKING.

    A point's absolute time is its curve's start plus its relative time, which can miss the
    transient's time by an ulp; within SAME_TIME counts as the same moment.
    """
    out, done = [], set()
    for t, v in points:
        k = int(np.searchsorted(marks, t))
        near = [m for m in marks[max(k - 1, 0) : k + 1].tolist() if abs(m - t) <= SAME_TIME]
        if near and near[0] not in done:
            done.add(near[0])
            v = min(1.0, v / DUCKING)
        out.append((t, v))
    return out


def _emphasis(transients, intensity: _Control, sharpness: _Control, felt: bool) -> list[Emphasis]:
    """The transients as emphasis: as Core Haptics plays them (the controls scale their
    intensity and shift their sharpness) where `felt`, else as written (Meta's converter means
    its transients to play apart from its curves, as its SplitAhap does)."""
    times = np.array([e["time"] for e in transients])
    scale = intensity.freeze().at(times) if felt else np.ones(len(times))
    shift = sharpness.freeze().at(times) if felt else np.zeros(len(times))
    return [
        Emphasis(
            e["time"], min(1.0, e["intensity"] * c) ** 2, min(1.0, max(0.0, e["sharpness"] + d))
        )
        for e, c, d in zip(transients, scale.tolist(), shift.tolist(), strict=True)
    ]


def read_design(path: Path) -> tuple[VibrationDesign, str, list[str]]:
    """The AHAP file's design, its sharpness convention, and notes on what was approximated."""
    text = vib.json_text(path, "AHAP")
    _refuse_long_pattern(text, path.name)
    doc = vib.parse_json(text, path.name, "AHAP")
    if not isinstance(doc, dict) or not isinstance(doc.get("Pattern"), list):
        raise FormatError(f"{path.name} is not an AHAP file (it has no Pattern list)")
    events, controls, notes = _entries(doc["Pattern"], path.name)
    if not events:
        raise FormatError(f"{path.name} holds no haptic events (no transient or continuous event)")
    convention = _convention(doc, events, controls)
    transients = [e for e in events if e["type"] == "HapticTransient"]
    if convention == "sqrt" and not _neutral(doc):  # undo the converter's ducking at emphasis
        at = np.unique([e["time"] for e in transients])
        controls = [
            (pid, start, _unducked(pts, at) if pid == "HapticIntensityControl" else pts)
            for pid, start, pts in controls
        ]
    intensity, sharpness = _Control(1.0), _Control(0.0)
    for pid, start, pts in sorted(controls, key=lambda c: c[1]):
        (intensity if pid == "HapticIntensityControl" else sharpness).set_from(start, pts)
    continuous = [e for e in events if e["type"] == "HapticContinuous" and e["duration"] > 0]
    amplitude: list[tuple[float, float]] = []
    frequency: list[tuple[float, float]] = []
    if continuous:
        player = _Player(continuous, intensity, sharpness)
        knots = _knots(player, controls)
        amplitude = _pairs(*_squared(knots, player, 0, FIT_TOLERANCE))
        if convention == "sqrt":
            frequency = _pairs(*_squared(knots, player, 1, FIT_TOLERANCE))
        else:
            frequency = _pairs(*_stepped(knots, player, 1))
    emphasis = _emphasis(transients, intensity, sharpness, felt=convention == "linear")
    ends = [t for t, _ in amplitude + frequency] + [e.time + e.length for e in emphasis]
    if not ends:
        raise FormatError(f"{path.name} holds no haptic events that last (every event lasts 0 s)")
    design = VibrationDesign(tuple(amplitude), tuple(frequency), tuple(emphasis), max(ends))
    return design, convention, notes


# --- writing: importers.ahap_writer ----------------------------------------------------------


class AhapFormat:
    """Apple AHAP: a pattern read into a vibration design and written back from one."""

    name = "ahap"
    extensions = (".ahap",)
    reads = "design"
    writes = "project"
    options: tuple[str, ...] = ()
    max_events = MAX_EVENTS

    def read(self, path: Path, *, progress: Progress | None = None, **options: Any) -> Imported:
        """The pattern as one vibration design on a drive track."""
        path = Path(path)
        design, convention, notes = read_design(path)
        if progress is not None:
            progress(1.0)
        return design_placements(design, path.stem, str(path), convention, tuple(notes))

    def write(self, source: Project, path: Path, rate: float | None = None, **options: Any) -> None:
        """Write the project's sounding drive tracks as an AHAP pattern."""
        convention = sharpness_convention(source)
        doc = {
            "Version": 1.0,
            "Metadata": {
                "Project": "",
                "Created": CREATED,
                "Description": SQRT_NOTE if convention == "sqrt" else LINEAR_NOTE,
                "Layout": NEUTRAL_NOTE,
            },
            "Pattern": design_pattern(design_of(source, rate=rate), convention),
        }
        vib.write_json(doc, path)


FORMAT = AhapFormat()
