"""A vibration design as an AHAP pattern that plays right under Core Haptics' documented rules.

Core Haptics applies intensity and sharpness controls to every event of a pattern, transients
included (docs/formats.md quotes Apple). So the pattern is laid out for the controls to be
neutral (intensity control 1, sharpness control 0) at every transient's time, while continuous
events still follow the design:

* Continuous events cover the amplitude envelope in pieces of at most 30 s at intensity 1 and
  sharpness 0, shaped by the controls (intensity control = sqrt(amplitude), sharpness control =
  the design's sharpness), as Meta's converter lays them out.
* At a transient inside the envelope a new continuous event starts, at the envelope's own
  intensity and sharpness there, so the controls restart at 1 and 0 (a curve that starts at a
  time sets its value from then on); the controls are the envelope divided by (minus) those
  event values. The event lasts until the envelope rises above its intensity, where an ordinary
  event takes over.
* Where the envelope rises right after a transient, it is held at its level there until it has
  risen by WRITE_TOLERANCE, then steps up (the error stays within the tolerance), so the
  control can be 1 at the transient; from silence that leaves the first WRITE_TOLERANCE of the
  rise silent, with the controls at 1 and 0.
* In silences after the envelope (or between parts of it) that hold transients, a short curve
  sets the controls back to 1 and 0.

Intensity is fitted where the player interpolates (module _envelope_fit): the heard amplitude
(intensity squared) is within WRITE_TOLERANCE of the design's straight segments; sharpness in
Meta's convention (sqrt of frequency) the same way. No ducking is added under an emphasis.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from importers._envelope_fit import roots_of_lines
from timeline.edits.vibration import VibrationDesign
from timeline.signal.vibration_design import DEFAULT_FREQUENCY

MAX_CONTINUOUS = 30.0  # s: Core Haptics' longest continuous event
MAX_CURVE_POINTS = 16  # Core Haptics' limit per parameter curve
WRITE_TOLERANCE = 0.01  # amplitude (and frequency): the player's curve vs the design
HOLD = 0.05  # s: how long neutral controls are held after the last transient of a pattern
INTENSITY, SHARPNESS = "HapticIntensityControl", "HapticSharpnessControl"

Points = list[tuple[float, float]]


def _offset(a: float, b: float) -> float:
    """b - a, nudged by an ulp where needed so that a + offset == b in floating point (the
    player adds a curve's or event's start to the relative times written); where no offset adds
    up to b exactly (0.438 + x skips 0.969), the one ending just before b, so nothing written to
    end at b (an event, the controls set for a transient there) reaches past it."""
    d = b - a
    down = math.nextafter(d, -math.inf)
    for candidate in (d, math.nextafter(d, math.inf), down):
        if a + candidate == b:
            return candidate
    return d if a + d < b else down


class _Piecewise:
    """Breakpoints (steps allowed) read at any time from the right or the left."""

    def __init__(self, t: np.ndarray, v: np.ndarray) -> None:
        self.t, self.v = np.asarray(t, dtype=np.float64), np.asarray(v, dtype=np.float64)

    def at(self, u: float, right: bool = True) -> float:
        k = int(np.searchsorted(self.t, u, side="right" if right else "left")) - 1
        if k < 0:
            return float(self.v[0])
        if k + 1 >= len(self.t):
            return float(self.v[-1])
        t0, t1 = self.t[k], self.t[k + 1]
        if t1 <= t0:
            return float(self.v[k + 1] if not right else self.v[k])
        w = (u - t0) / (t1 - t0)
        return float(self.v[k] + w * (self.v[k + 1] - self.v[k]))

    def inside(self, a: float, b: float) -> Points:
        """The piece from a (value from the right) to b (from the left), breakpoints between."""
        lo = int(np.searchsorted(self.t, a, side="right"))
        hi = int(np.searchsorted(self.t, b, side="left"))
        middle = list(zip(self.t[lo:hi].tolist(), self.v[lo:hi].tolist(), strict=True))
        return [(a, self.at(a)), *middle, (b, self.at(b, right=False))]

    def first_above(self, a: float, b: float, level: float) -> float:
        """The first time in [a, b) where the value rises above `level` (b if it never does)."""
        piece = self.inside(a, b)
        for (t0, v0), (t1, v1) in zip(piece, piece[1:], strict=False):
            if v1 > level + 1e-12:
                if v0 >= level or t1 <= t0:
                    return t0
                return t0 + (level - v0) / (v1 - v0) * (t1 - t0)
        return b


def _with_gaps(amplitude: Points, marks: list[float]) -> tuple[Points, list[float]]:
    """The amplitude with a breakpoint at every mark inside it, and where it rises right after a
    mark, held at the mark's level until it has risen by WRITE_TOLERANCE (then a step up): the
    controls can then be neutral at the mark (see the module's docstring). Also the times the
    intensity fit must keep as breakpoints."""
    t = np.array([p[0] for p in amplitude])
    v = np.array([p[1] for p in amplitude])
    inserted = [(m, float(np.interp(m, t, v))) for m in marks if t[0] < m < t[-1] and m not in t]
    out = sorted(amplitude + inserted, key=lambda p: p[0])  # stable: steps keep their order
    chosen = set(marks)
    result: Points = []
    keep = []
    for k, (time, level) in enumerate(out):
        result.append((time, level))
        if time not in chosen or (k + 1 < len(out) and out[k + 1][0] == time):
            continue  # not a mark, or not the last breakpoint at it (the value from the right)
        keep.append(time)
        if k + 1 < len(out) and out[k + 1][1] > level:
            t1, a1 = out[k + 1]
            frac = min(1.0, WRITE_TOLERANCE / (a1 - level))
            step = time + (t1 - time) * frac
            result += [(step, level), (step, level + (a1 - level) * frac)]
            keep.append(step)
    return result, sorted(set(keep))


def _intensity(amplitude: Points, keep: list[float]) -> _Piecewise:
    """Intensity breakpoints for the amplitude, fitted piece by piece between the kept times."""
    t = np.array([p[0] for p in amplitude])
    v = np.array([p[1] for p in amplitude])
    cuts = np.unique(np.concatenate([[0, len(t) - 1], np.searchsorted(t, keep)]))
    cuts = cuts[cuts < len(t)]
    pieces = [
        roots_of_lines(t[a : b + 1], v[a : b + 1], WRITE_TOLERANCE)
        for a, b in zip(cuts, cuts[1:], strict=False)
    ] or [roots_of_lines(t, v, WRITE_TOLERANCE)]
    tt = np.concatenate([pieces[0][0]] + [p[0][1:] for p in pieces[1:]])
    rr = np.concatenate([pieces[0][1]] + [p[1][1:] for p in pieces[1:]])
    return _Piecewise(tt, rr)


def _sharpness(design: VibrationDesign, start: float, end: float, convention: str) -> _Piecewise:
    """The design's sharpness over [start, end] in the file's convention (sqrt fitted)."""
    freq = list(design.frequency) or [(start, DEFAULT_FREQUENCY)]
    if freq[0][0] > start:
        freq.insert(0, (start, freq[0][1]))
    if freq[-1][0] < end:
        freq.append((end, freq[-1][1]))
    t = np.array([p[0] for p in freq])
    f = np.array([p[1] for p in freq])
    if convention == "sqrt":
        return _Piecewise(*roots_of_lines(t, f, WRITE_TOLERANCE))
    return _Piecewise(t, f)


def _event(kind: str, time: float, intensity: float, sharp: float, end: float | None = None):
    event: dict[str, Any] = {"Time": time, "EventType": kind}
    if end is not None:
        event["EventDuration"] = _offset(time, end)
    event["EventParameters"] = [
        {"ParameterID": "HapticIntensity", "ParameterValue": intensity},
        {"ParameterID": "HapticSharpness", "ParameterValue": sharp},
    ]
    return {"Event": event}


def _curves(pid: str, points: Points) -> list[dict[str, Any]]:
    """Curves of at most 16 control points (times relative), each starting where the last ended."""
    curves = []
    i = 0
    while True:
        chunk = points[i : i + MAX_CURVE_POINTS]
        start = chunk[0][0]
        controls = [{"Time": _offset(start, t), "ParameterValue": v} for t, v in chunk]
        curves.append(
            {
                "ParameterCurve": {
                    "ParameterID": pid,
                    "Time": start,
                    "ParameterCurveControlPoints": controls,
                }
            }
        )
        i += MAX_CURVE_POINTS - 1
        if i >= len(points) - 1:
            return curves


class _Layout:
    """The pattern being built: events and both controls, each control's held value tracked so
    a curve that changes nothing is left out."""

    def __init__(self) -> None:
        self.pattern: list[dict[str, Any]] = []
        self.held = {INTENSITY: 1.0, SHARPNESS: 0.0}

    def control(self, pid: str, points: Points) -> None:
        if all(v == self.held[pid] for _, v in points):
            return
        self.pattern += _curves(pid, points)
        self.held[pid] = points[-1][1]

    def neutral(self, start: float, end: float) -> None:
        """Controls at 1 and 0 over [start, end] (a silence that holds transients)."""
        end = max(end, start + HOLD)
        self.control(INTENSITY, [(start, 1.0), (end, 1.0)])
        self.control(SHARPNESS, [(start, 0.0), (end, 0.0)])

    def continuous(self, a: float, b: float, level: float, sharp: float, r, s) -> None:
        """A continuous event over [a, b) at (level, sharp), the controls making up the rest."""
        self.pattern.append(_event("HapticContinuous", a, level, sharp, b))
        self.control(INTENSITY, [(t, min(1.0, v / level)) for t, v in r.inside(a, b)])
        self.control(SHARPNESS, [(t, v - sharp) for t, v in s.inside(a, b)])

    def ordinary(self, a: float, b: float, r, s) -> None:
        """Events at intensity 1 and sharpness 0 over [a, b), at most 30 s each."""
        while b - a > 1e-12:
            end = min(a + MAX_CONTINUOUS, b)
            self.continuous(a, end, 1.0, 0.0, r, s)
            a = end


def design_pattern(design: VibrationDesign, convention: str) -> list[dict[str, Any]]:
    """AHAP pattern entries for a design, in the given sharpness convention."""
    amplitude = list(design.amplitude)
    if len(amplitude) < 2 or amplitude[-1][0] <= amplitude[0][0]:
        amplitude = [] if design.emphasis else [(0.0, 0.0), (design.duration, 0.0)]
    marks = sorted({e.time for e in design.emphasis})
    layout = _Layout()
    if amplitude:
        start, end = amplitude[0][0], amplitude[-1][0]
        amplitude, keep = _with_gaps(amplitude, [m for m in marks if start <= m < end])
        r = _intensity(amplitude, keep)
        s = _sharpness(design, start, end, convention)
        _lay_out(layout, r, s, start, end, [m for m in marks if start <= m < end])
        after = [m for m in marks if m >= end]
        if after:
            layout.neutral(end, after[-1])
    for e in design.emphasis:
        layout.pattern.append(
            _event("HapticTransient", e.time, math.sqrt(e.amplitude), e.frequency)
        )
    layout.pattern.sort(key=lambda p: next(iter(p.values()))["Time"])
    return layout.pattern


def _lay_out(layout: _Layout, r: _Piecewise, s: _Piecewise, start, end, marks) -> None:
    """Continuous events and controls over the envelope [start, end], transients at `marks`."""
    bounds = sorted({start, end, *marks})
    for a, b in zip(bounds, bounds[1:], strict=False):
        if a not in marks:
            layout.ordinary(a, b, r, s)
            continue
        level = r.at(a)
        if level > 0.0:
            rise = min(r.first_above(a, b, level), a + MAX_CONTINUOUS)
            if rise > a:  # (a rise within an ulp of the transient leaves no room)
                layout.continuous(a, rise, level, s.at(a), r, s)
            layout.ordinary(rise, b, r, s)
            continue
        sounding = r.first_above(a, b, 0.0)  # the gap left silent after the transient
        layout.neutral(a, sounding)
        layout.ordinary(sounding, b, r, s)
