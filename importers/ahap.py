"""Apple AHAP (Core Haptics JSON): transient and continuous events, parameter curves.

Reading: HapticTransient and HapticContinuous events with HapticIntensity/HapticSharpness, the
continuous events' Attack/Decay/Release envelope, HapticIntensityControl (a multiplier) and
HapticSharpnessControl (an offset) as dynamic parameters or curves become drive clips; the
controls shape continuous events only (transients keep their own values, as in files made by
Lofelt's converter). Actuator
amplitude is intensity squared, as Lofelt's converter writes it. Audio events are skipped.
Writing: the drive layer is analysed into intensity and sharpness curves (at most 16 control
points each, chained) over continuous events of at most 30 s, and transients.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np

from importers import _vibration as vib
from timeline.formats import FormatError, Imported, Progress
from timeline.model import DEFAULT_TIME_RATE, Project

MAX_CONTINUOUS = 30.0  # s: Core Haptics' longest continuous event
MAX_CURVE_POINTS = 16  # Core Haptics' limit per parameter curve
DEFAULT_INTENSITY = 1.0
DEFAULT_SHARPNESS = 0.5


def _parameters(event: dict[str, Any], where: str) -> dict[str, float]:
    found: dict[str, float] = {}
    params = event.get("EventParameters", [])
    if not isinstance(params, list):
        raise FormatError(f"{where}: EventParameters must be a list")
    for p in params:
        if not isinstance(p, dict) or not isinstance(p.get("ParameterID"), str):
            raise FormatError(f"{where}: each event parameter needs a ParameterID")
        pid = p["ParameterID"]
        lo = (
            0.0
            if pid
            in ("HapticIntensity", "HapticSharpness", "AttackTime", "DecayTime", "ReleaseTime")
            else -math.inf
        )
        if pid == "Sustained":
            found[pid] = float(bool(p.get("ParameterValue", True)))
        else:
            found[pid] = vib.number(p.get("ParameterValue"), f"{where}: {pid}", lo)
    return found


class _Control:
    """A control value over the sample grid, set by dynamic parameters and curves in time order."""

    def __init__(self, n: int, rate: float, default: float) -> None:
        self.t = np.arange(n) / rate
        self.values = np.full(n, default)

    def step(self, time: float, value: float) -> None:
        self.values[np.searchsorted(self.t, time) :] = value

    def curve(self, times: np.ndarray, values: np.ndarray) -> None:
        i0 = np.searchsorted(self.t, times[0])
        self.values[i0:] = np.interp(self.t[i0:], times, values)


class AhapFormat:
    """Apple AHAP: reads events and curves into drive clips; writes a drive layer."""

    name = "ahap"
    extensions = (".ahap",)
    reads = "design"
    writes = "project"
    options = ("rate",)

    def read(
        self,
        path: Path,
        *,
        progress: Progress | None = None,
        rate: float | None = None,
        **options: Any,
    ) -> Imported:
        """Synthesise the pattern's drive waveform at `rate` (default 10 kHz)."""
        path = Path(path)
        rate = float(rate or DEFAULT_TIME_RATE)
        doc = vib.load_json(path, "AHAP")
        if not isinstance(doc, dict) or not isinstance(doc.get("Pattern"), list):
            raise FormatError(f"{path.name} is not an AHAP file (it has no Pattern list)")
        events, controls, notes = self._entries(doc["Pattern"], path.name)
        ends = [e["time"] + e.get("duration", 0.0) for e in events]
        if not events:
            raise FormatError(f"{path.name} holds no haptic events")
        n = vib.grid_length(max(ends) + 0.05, rate)
        intensity = _Control(n, rate, 1.0)
        sharp_offset = _Control(n, rate, 0.0)
        for kind, time, times, values in sorted(controls, key=lambda c: c[1]):
            target = intensity if kind == "HapticIntensityControl" else sharp_offset
            if times is None:
                target.step(time, values)
            else:
                target.curve(times, values)
        placements = []
        continuous = [e for e in events if e["type"] == "HapticContinuous"]
        if continuous:
            placements.append(self._continuous(continuous, intensity, sharp_offset, rate, path))
        for e in events:  # controls shape continuous events only, as Lofelt's converter assumes
            if e["type"] == "HapticTransient":
                placements.append(
                    vib.transient_placement(e["time"], e["intensity"] ** 2, e["sharpness"])
                )
        if progress is not None:
            progress(1.0)
        return vib.imported(placements, notes, path.name)

    @staticmethod
    def _continuous(events, intensity, sharp_offset, rate, path):
        t = intensity.t
        level = np.zeros(len(t))
        sharp = np.zeros(len(t))
        for e in events:
            local = t - e["time"]
            inside = (local >= 0) & (local <= e["duration"])
            env = _adsr(local[inside], e)
            level[inside] += e["intensity"] * env * intensity.values[inside]
            sharp[inside] = e["sharpness"] + sharp_offset.values[inside]
        first = min(e["time"] for e in events)
        last = max(e["time"] + e["duration"] for e in events)
        i0, i1 = int(np.searchsorted(t, first)), int(np.searchsorted(t, last, side="right"))
        amplitude = np.clip(level[i0:i1], 0.0, 1.0) ** 2
        return vib.continuous_placement(
            amplitude,
            np.clip(sharp[i0:i1], 0.0, 1.0),
            rate,
            float(t[i0]),
            f"{path.stem} continuous",
            str(path),
        )

    @staticmethod
    def _entries(pattern: list[Any], name: str):
        events: list[dict[str, Any]] = []
        controls: list[tuple[str, float, Any, Any]] = []
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
                control = _curve(entry["ParameterCurve"], where)
                if control is not None:
                    controls.append(control)
            elif "Parameter" in entry:
                control = _dynamic(entry["Parameter"], where)
                if control is not None:
                    controls.append(control)
            else:
                raise FormatError(f"{where} is not an Event, ParameterCurve or Parameter")
        return events, controls, notes

    def write(self, source: Project, path: Path, rate: float | None = None, **options: Any) -> None:
        """Write the project's sounding drive tracks as an AHAP pattern."""
        analysis = vib.analyse(source, rate)
        pattern: list[dict[str, Any]] = []
        sounding = any(v > 0 for _, v in analysis.amplitude)
        if sounding:
            start, end = analysis.amplitude[0][0], analysis.amplitude[-1][0]
            t = start
            while t < end:
                length = min(MAX_CONTINUOUS, end - t)
                pattern.append(_event_json("HapticContinuous", t, 1.0, 0.0, length))
                t += length
            intensity = [(tt, math.sqrt(v)) for tt, v in analysis.amplitude]
            pattern += _curves("HapticIntensityControl", intensity)
            pattern += _curves("HapticSharpnessControl", analysis.sharpness)
        for tr in analysis.transients:
            pattern.append(
                _event_json("HapticTransient", tr.time, math.sqrt(tr.intensity), tr.sharpness)
            )
        if not pattern:
            raise FormatError("the project's drive layer is silent: there is nothing to export")
        pattern.sort(key=lambda p: next(iter(p.values()))["Time"])
        doc = {
            "Version": 1.0,
            "Metadata": {"Project": "", "Created": "haptic-timeline", "Description": ""},
            "Pattern": pattern,
        }
        vib.write_json(doc, path)


def _adsr(local: np.ndarray, e: dict[str, Any]) -> np.ndarray:
    """An approximation of Core Haptics' continuous-event envelope (attack, decay, release)."""
    env = np.ones(len(local))
    if e["attack"] > 0:
        env = np.minimum(env, local / e["attack"])
    if not e["sustained"] and e["decay"] > 0:
        env = np.minimum(env, np.clip(1.0 - (local - e["attack"]) / e["decay"], 0.0, 1.0))
    if e["release"] > 0:
        env = np.minimum(env, np.clip((e["duration"] - local) / e["release"], 0.0, 1.0))
    return np.clip(env, 0.0, 1.0)


def _event(event: Any, where: str, notes: list[str]) -> dict[str, Any] | None:
    if not isinstance(event, dict) or not isinstance(event.get("EventType"), str):
        raise FormatError(f"{where}: an Event needs an EventType")
    kind = event["EventType"]
    if kind not in ("HapticTransient", "HapticContinuous"):
        notes.append(f"{kind} events are not haptic and were skipped")
        return None
    params = _parameters(event, where)
    out = {
        "type": kind,
        "time": vib.number(event.get("Time"), f"{where}: Time", 0.0, vib.MAX_DURATION),
        "intensity": min(params.get("HapticIntensity", DEFAULT_INTENSITY), 1.0),
        "sharpness": min(params.get("HapticSharpness", DEFAULT_SHARPNESS), 1.0),
    }
    if kind == "HapticContinuous":
        out["duration"] = vib.number(
            event.get("EventDuration"), f"{where}: EventDuration", 0.0, vib.MAX_DURATION
        )
        if out["duration"] > MAX_CONTINUOUS:
            notes.append(f"a continuous event is longer than Core Haptics' {MAX_CONTINUOUS:g} s")
        out["attack"] = params.get("AttackTime", 0.0)
        out["decay"] = params.get("DecayTime", 0.0)
        out["release"] = params.get("ReleaseTime", 0.0)
        out["sustained"] = bool(params.get("Sustained", 1.0))
    return out


def _control_range(pid: str) -> tuple[float, float] | None:
    return {"HapticIntensityControl": (0.0, 1.0), "HapticSharpnessControl": (-1.0, 1.0)}.get(pid)


def _curve(curve: Any, where: str) -> tuple[str, float, np.ndarray, np.ndarray] | None:
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
    for p in points:
        if not isinstance(p, dict):
            raise FormatError(f"{where}: each control point must be an object")
        times.append(vib.number(p.get("Time"), f"{where}: control point Time", 0.0))
        values.append(vib.number(p.get("ParameterValue"), f"{where}: control point value", *bounds))
    times_a = np.array(times)
    if np.any(np.diff(times_a) < 0):
        raise FormatError(f"{where}: control point times go backwards")
    # Apple's control point times are relative to the curve; Lofelt's converter writes them
    # absolute (the first equals the curve's Time). Accept both.
    if not (start > 0 and times_a[0] == start):
        times_a = times_a + start
    return pid, float(times_a[0]), times_a, np.array(values)


def _dynamic(param: Any, where: str) -> tuple[str, float, None, float] | None:
    if not isinstance(param, dict):
        raise FormatError(f"{where}: a Parameter must be an object")
    pid = param.get("ParameterID")
    bounds = _control_range(pid) if isinstance(pid, str) else None
    if bounds is None:
        return None
    time = vib.number(param.get("Time"), f"{where}: Time", 0.0, vib.MAX_DURATION)
    return pid, time, None, vib.number(param.get("ParameterValue"), f"{where}: value", *bounds)


def _event_json(
    kind: str, time: float, intensity: float, sharp: float, duration: float | None = None
) -> dict[str, Any]:
    event: dict[str, Any] = {"Time": time, "EventType": kind}
    if duration is not None:
        event["EventDuration"] = duration
    event["EventParameters"] = [
        {"ParameterID": "HapticIntensity", "ParameterValue": round(intensity, 6)},
        {"ParameterID": "HapticSharpness", "ParameterValue": round(sharp, 6)},
    ]
    return {"Event": event}


def _curves(pid: str, points: list[tuple[float, float]]) -> list[dict[str, Any]]:
    """Curves of at most 16 control points, each starting where the previous one ended."""
    curves = []
    i = 0
    while True:
        chunk = points[i : i + MAX_CURVE_POINTS]
        start = chunk[0][0]
        curves.append(
            {
                "ParameterCurve": {
                    "ParameterID": pid,
                    "Time": start,
                    "ParameterCurveControlPoints": [
                        {"Time": t - start, "ParameterValue": round(v, 6)} for t, v in chunk
                    ],
                }
            }
        )
        i += MAX_CURVE_POINTS - 1
        if i >= len(points) - 1:
            return curves


FORMAT = AhapFormat()
