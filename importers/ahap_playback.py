"""AHAP as Core Haptics documents playing it: felt transients and continuous vibration over time.

Used to check exports, independently of the reader (importers.ahap): it follows only Apple's
documented rules (docs/formats.md quotes them).

* Events: `HapticTransient` at `Time`; `HapticContinuous` over [Time, Time + EventDuration),
  shaped by AttackTime/DecayTime/ReleaseTime (linear ramps) and Sustained. Missing
  HapticIntensity reads 1, missing HapticSharpness 0.5; values are clamped to 0..1, as Core
  Haptics does on load.
* Controls apply to **every** event, transients included: felt intensity = event intensity x
  HapticIntensityControl; felt sharpness = event sharpness + HapticSharpnessControl; each
  clamped to 0..1. Without a control, intensity control is 1 and sharpness control 0.
* A `ParameterCurve` starting at T interpolates linearly from the value in force just before T
  to its control points (times relative to T) and holds its last value; a dynamic `Parameter`
  changes the value abruptly at its time. A later entry replaces the earlier ones from its start.
* Overlapping continuous events (their mix is not documented) add their intensities, clamped to
  1; the latest-starting one gives the sharpness.
"""

from __future__ import annotations

import bisect
from dataclasses import dataclass
from typing import Any

import numpy as np

INTENSITY, SHARPNESS = "HapticIntensityControl", "HapticSharpnessControl"
DEFAULTS = {INTENSITY: 1.0, SHARPNESS: 0.0}
BOUNDS = {INTENSITY: (0.0, 1.0), SHARPNESS: (-1.0, 1.0)}


def _clamp(value: float, lo: float = 0.0, hi: float = 1.0) -> float:
    return min(hi, max(lo, float(value)))


class Control:
    """One dynamic parameter over time: knots (time, value), linear between, a later knot at
    the same time a step; right-continuous."""

    def __init__(self, default: float) -> None:
        self.t: list[float] = []
        self.v: list[float] = []
        self.default = default

    def _before(self, s: float) -> float:
        """The value just before time s."""
        k = bisect.bisect_left(self.t, s) - 1
        if k < 0:
            return self.default
        if k + 1 < len(self.t) and self.t[k + 1] > self.t[k]:
            w = (s - self.t[k]) / (self.t[k + 1] - self.t[k])
            return self.v[k] + w * (self.v[k + 1] - self.v[k])
        return self.v[k]

    def apply(self, start: float, points: list[tuple[float, float]]) -> None:
        """From `start` on, follow `points` (absolute times; one point for a Parameter)."""
        before = self._before(start)
        k = bisect.bisect_left(self.t, start)
        del self.t[k:], self.v[k:]
        self.t += [start] + [p[0] for p in points]
        self.v += [before] + [p[1] for p in points]

    def at(self, u: np.ndarray) -> np.ndarray:
        """Values at times u."""
        u = np.asarray(u, dtype=np.float64)
        if not self.t:
            return np.full(u.shape, self.default)
        t, v = np.array(self.t), np.array(self.v)
        k = np.searchsorted(t, u, side="right") - 1
        out = np.full(u.shape, self.default)
        inside = k >= 0
        kk = np.clip(k, 0, len(t) - 1)
        nxt = np.minimum(kk + 1, len(t) - 1)
        width = t[nxt] - t[kk]
        slope = np.where(width > 0, (v[nxt] - v[kk]) / np.where(width > 0, width, 1.0), 0.0)
        return np.where(inside, v[kk] + slope * (u - t[kk]), out)


@dataclass(frozen=True)
class Playback:
    """What a pattern plays: transients (time, felt intensity, felt sharpness) and continuous
    events, with the controls that shape both."""

    transients: list[tuple[float, float, float]]
    continuous: list[dict[str, float]]
    controls: dict[str, Control]

    def continuous_at(self, u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Felt continuous intensity and sharpness at times u (0 and 0 where nothing plays)."""
        u = np.asarray(u, dtype=np.float64)
        level, sharp = np.zeros(u.shape), np.zeros(u.shape)
        playing = np.zeros(u.shape, dtype=bool)
        for e in sorted(self.continuous, key=lambda e: e["time"]):
            inside = (u >= e["time"]) & (u < e["time"] + e["duration"])
            level[inside] += e["intensity"] * _envelope(u[inside] - e["time"], e)
            sharp[inside] = e["sharpness"]
            playing |= inside
        level = np.clip(level * self.controls[INTENSITY].at(u), 0.0, 1.0)
        sharp = np.clip(sharp + self.controls[SHARPNESS].at(u), 0.0, 1.0)
        return level, np.where(playing, sharp, 0.0)


def _envelope(local: np.ndarray, e: dict[str, float]) -> np.ndarray:
    env = np.ones(local.shape)
    if e["attack"] > 0:
        env = np.minimum(env, local / e["attack"])
    if not e["sustained"] and e["decay"] > 0:
        env = np.minimum(env, 1.0 - (local - e["attack"]) / e["decay"])
    if e["release"] > 0:
        env = np.minimum(env, (e["duration"] - local) / e["release"])
    return np.clip(env, 0.0, 1.0)


def _parameters(event: dict[str, Any]) -> dict[str, float]:
    return {
        p["ParameterID"]: p.get("ParameterValue", 1.0)
        for p in event.get("EventParameters", [])
        if isinstance(p, dict) and "ParameterID" in p
    }


def playback(doc: dict[str, Any]) -> Playback:
    """Evaluate an AHAP document (parsed JSON) as Core Haptics documents playing it."""
    events: list[dict[str, Any]] = []
    applied: list[tuple[float, int, str, list[tuple[float, float]]]] = []
    for k, entry in enumerate(doc.get("Pattern", [])):
        if "Event" in entry:
            events.append(entry["Event"])
        curve, param = entry.get("ParameterCurve"), entry.get("Parameter")
        if curve is not None and curve.get("ParameterID") in BOUNDS:
            pid, start = curve["ParameterID"], float(curve.get("Time", 0.0))
            points = [
                (start + float(p["Time"]), _clamp(p["ParameterValue"], *BOUNDS[pid]))
                for p in curve["ParameterCurveControlPoints"]
            ]
            applied.append((start, k, pid, points))
        if param is not None and param.get("ParameterID") in BOUNDS:
            pid, start = param["ParameterID"], float(param.get("Time", 0.0))
            applied.append(
                (start, k, pid, [(start, _clamp(param["ParameterValue"], *BOUNDS[pid]))])
            )
    controls = {pid: Control(default) for pid, default in DEFAULTS.items()}
    for start, _, pid, points in sorted(applied, key=lambda a: (a[0], a[1])):
        controls[pid].apply(start, points)
    transients, continuous = [], []
    for event in events:
        kind = str(event.get("EventType", "")).lower()
        params = _parameters(event)
        intensity = _clamp(params.get("HapticIntensity", 1.0))
        sharpness = _clamp(params.get("HapticSharpness", 0.5))
        time = float(event.get("Time", 0.0))
        if kind == "haptictransient":
            transients.append((time, intensity, sharpness))
        elif kind == "hapticcontinuous":
            continuous.append(
                {
                    "time": time,
                    "duration": float(event.get("EventDuration", 0.0)),
                    "intensity": intensity,
                    "sharpness": sharpness,
                    "attack": float(params.get("AttackTime", 0.0)),
                    "decay": float(params.get("DecayTime", 0.0)),
                    "release": float(params.get("ReleaseTime", 0.0)),
                    "sustained": bool(params.get("Sustained", True)),
                }
            )
    times = np.array([t for t, _, _ in transients])
    scale, shift = controls[INTENSITY].at(times), controls[SHARPNESS].at(times)
    felt = [
        (t, _clamp(i * c), _clamp(s + d))
        for (t, i, s), c, d in zip(transients, scale.tolist(), shift.tolist(), strict=True)
    ]
    return Playback(sorted(felt), continuous, controls)
