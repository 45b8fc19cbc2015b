"""Meta Haptics Studio / Lofelt `.haptic` (v1 JSON): amplitude and frequency envelopes, emphasis.

Reading: the amplitude envelope (0..1) and frequency envelope (0..1, mapped to a carrier as
sharpness is) become one sampled drive clip from the first to the last amplitude breakpoint;
each emphasis becomes a transient clip at its breakpoint. Writing: the drive layer's analysed
envelopes, with transients as emphasis on amplitude breakpoints at their times.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from importers import _vibration as vib
from timeline.formats import FormatError, Imported, Progress
from timeline.model import DEFAULT_TIME_RATE, Project

DEFAULT_FREQUENCY = 0.5
SAME_TIME = 1e-9  # s: a transient this close to a breakpoint becomes its emphasis


def _breakpoints(items: Any, key: str, where: str) -> list[dict[str, Any]]:
    if not isinstance(items, list):
        raise FormatError(f"{where}: the {key} envelope must be a list of breakpoints")
    out = []
    previous = 0.0
    for k, bp in enumerate(items):
        here = f"{where}: {key} breakpoint {k + 1}"
        if not isinstance(bp, dict):
            raise FormatError(f"{here} is not an object")
        time = vib.number(bp.get("time"), f"{here} time", 0.0, vib.MAX_DURATION)
        if time < previous:
            raise FormatError(f"{here} goes back in time ({time:g} s after {previous:g} s)")
        previous = time
        entry = {"time": time, "value": vib.number(bp.get(key), f"{here} {key}", 0.0, 1.0)}
        emphasis = bp.get("emphasis")
        if emphasis is not None:
            if not isinstance(emphasis, dict):
                raise FormatError(f"{here} emphasis must be an object")
            entry["emphasis"] = (
                vib.number(emphasis.get("amplitude"), f"{here} emphasis amplitude", 0.0, 1.0),
                vib.number(emphasis.get("frequency"), f"{here} emphasis frequency", 0.0, 1.0),
            )
        out.append(entry)
    return out


class LofeltFormat:
    """Lofelt / Meta Haptics Studio .haptic: envelopes to drive clips, a drive layer back."""

    name = "haptic"
    extensions = (".haptic",)
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
        """Synthesise the envelopes' drive waveform at `rate` (default 10 kHz)."""
        path = Path(path)
        rate = float(rate or DEFAULT_TIME_RATE)
        doc = vib.load_json(path, ".haptic")
        if not isinstance(doc, dict):
            raise FormatError(f"{path.name} is not a .haptic file (it is not a JSON object)")
        _check_version(doc.get("version"), path.name)
        envelopes = _envelopes(doc, path.name)
        amplitude = _breakpoints(envelopes.get("amplitude"), "amplitude", path.name)
        if not amplitude:
            raise FormatError(f"{path.name} has an empty amplitude envelope")
        notes: list[str] = []
        if "frequency" in envelopes:
            frequency = _breakpoints(envelopes["frequency"], "frequency", path.name)
        else:
            frequency = []
            notes.append(f"no frequency envelope: sharpness {DEFAULT_FREQUENCY} assumed")
        placements = []
        first, last = amplitude[0]["time"], amplitude[-1]["time"]
        if last > first:
            n = vib.grid_length(last - first, rate)
            t = first + np.arange(n) / rate
            t = t[t <= last]
            amp = np.interp(t, [b["time"] for b in amplitude], [b["value"] for b in amplitude])
            if frequency:
                ft = [b["time"] for b in frequency]
                sharp = np.interp(t, ft, [b["value"] for b in frequency])
            else:
                sharp = np.full(len(t), DEFAULT_FREQUENCY)
            placements.append(
                vib.continuous_placement(amp, sharp, rate, first, f"{path.stem}", str(path))
            )
        for b in amplitude:
            if "emphasis" in b:
                level, sharp_e = b["emphasis"]
                if level < b["value"]:
                    notes.append(f"the emphasis at {b['time']:g} s is weaker than its breakpoint")
                placements.append(vib.transient_placement(b["time"], level, sharp_e))
        if progress is not None:
            progress(1.0)
        return vib.imported(placements, notes, path.name)

    def write(self, source: Project, path: Path, rate: float | None = None, **options: Any) -> None:
        """Write the project's sounding drive tracks as a v1 .haptic file."""
        analysis = vib.analyse(source, rate)
        amplitude = [{"time": t, "amplitude": v} for t, v in analysis.amplitude]
        for tr in analysis.transients:
            bp = next((b for b in amplitude if abs(b["time"] - tr.time) <= SAME_TIME), None)
            if bp is None:
                bp = {"time": tr.time, "amplitude": _level_at(analysis.amplitude, tr.time)}
                amplitude.append(bp)
                amplitude.sort(key=lambda b: b["time"])
            emphasis = bp.get("emphasis", {"amplitude": 0.0, "frequency": 0.0})
            if tr.intensity >= emphasis["amplitude"]:
                bp["emphasis"] = {
                    "amplitude": round(tr.intensity, 9),
                    "frequency": round(tr.sharpness, 9),
                }
        if not amplitude:
            raise FormatError("the project's drive layer is silent: there is nothing to export")
        doc = {
            "version": {"major": 1, "minor": 0, "patch": 0},
            "metadata": {
                "editor": "haptic-timeline",
                "author": "",
                "source": "",
                "project": "",
                "tags": [],
                "description": "",
            },
            "signals": {
                "continuous": {
                    "envelopes": {
                        "amplitude": amplitude,
                        "frequency": [{"time": t, "frequency": v} for t, v in analysis.sharpness],
                    }
                }
            },
        }
        vib.write_json(doc, path)


def _level_at(points: list[tuple[float, float]], time: float) -> float:
    if not points or time < points[0][0] or time > points[-1][0]:
        return 0.0
    return round(float(np.interp(time, [p[0] for p in points], [p[1] for p in points])), 6)


def _check_version(version: Any, name: str) -> None:
    if not isinstance(version, dict):
        raise FormatError(f"{name} is not a .haptic file (it has no version)")
    major = version.get("major")
    if major != 1 or isinstance(major, bool):
        raise FormatError(f"{name} is .haptic version {major!r}; only version 1 is supported")


def _envelopes(doc: dict[str, Any], name: str) -> dict[str, Any]:
    signals = doc.get("signals")
    continuous = signals.get("continuous") if isinstance(signals, dict) else None
    envelopes = continuous.get("envelopes") if isinstance(continuous, dict) else None
    if not isinstance(envelopes, dict):
        raise FormatError(f"{name} is not a .haptic file (no signals.continuous.envelopes)")
    return envelopes


FORMAT = LofeltFormat()
