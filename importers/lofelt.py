"""Meta Haptics Studio / Lofelt `.haptic` (v1 JSON): amplitude and frequency envelopes, emphasis.

Reading keeps the file's breakpoints and emphasis as one vibration design
(timeline.edits.vibration), so an unedited import -> export writes the same numbers back. Validity
follows Meta's validator: an amplitude envelope needs two breakpoints and a positive duration,
values lie in 0..1, times never go back; what Meta only flags for files from older tools (an
emphasis weaker than its breakpoint, frequency breakpoints past the amplitude envelope) is kept and
reported as a note. Writing takes timeline.edits.vibration.design_of of the sounding drive tracks:
each emphasis on an amplitude breakpoint at its time (one is inserted when none is free there, so
two emphases at one time both survive; one before the envelope's start is silent there), raised
to the envelope's level where it was weaker, as Meta's validator requires.
"""

from __future__ import annotations

from collections import deque
from pathlib import Path
from typing import Any

import numpy as np

from importers import _vibration as vib
from timeline.edits.vibration import (
    Emphasis,
    VibrationDesign,
    design_of,
    design_placements,
    sharpness_convention,
)
from timeline.model import Project
from timeline.plugins.file_formats import FormatError, Imported, Progress
from timeline.signal.vibration_design import DEFAULT_FREQUENCY


def _breakpoints(items: Any, key: str, where: str) -> list[dict[str, Any]]:
    if not isinstance(items, list):
        raise FormatError(f"{where}: the {key} envelope must be a list of breakpoints")
    out = []
    previous = 0.0
    for k, bp in enumerate(items):
        here = f"{where}: {key} breakpoint {k + 1}"
        if not isinstance(bp, dict):
            raise FormatError(f"{here} is not an object")
        for field in ("time", key):
            if field not in bp:
                raise FormatError(f"{here} has no {field}")
        time = vib.number(bp["time"], f"{here} time", 0.0, vib.MAX_DURATION)
        if time < previous:
            raise FormatError(f"{here} goes back in time ({time:g} s after {previous:g} s)")
        previous = time
        entry = {"time": time, "value": vib.number(bp[key], f"{here} {key}", 0.0, 1.0)}
        emphasis = bp.get("emphasis")
        if emphasis is not None:
            if not isinstance(emphasis, dict):
                raise FormatError(f"{here} emphasis must be an object")
            for field in ("amplitude", "frequency"):
                if field not in emphasis:
                    raise FormatError(f"{here} emphasis has no {field}")
            entry["emphasis"] = (
                vib.number(emphasis["amplitude"], f"{here} emphasis amplitude", 0.0, 1.0),
                vib.number(emphasis["frequency"], f"{here} emphasis frequency", 0.0, 1.0),
            )
        out.append(entry)
    return out


def read_design(path: Path) -> tuple[VibrationDesign, list[str]]:
    """The .haptic file's design, and notes on what Meta's validator would flag."""
    design, notes, _ = read_with_convention(path)
    return design, notes


def read_with_convention(path: Path) -> tuple[VibrationDesign, list[str], str]:
    """read_design, and the AHAP sharpness convention the design keeps (_convention)."""
    doc = vib.load_json(path, ".haptic")
    if not isinstance(doc, dict):
        raise FormatError(f"{path.name} is not a .haptic file (it is not a JSON object)")
    _check_version(doc.get("version"), path.name)
    envelopes = _envelopes(doc, path.name)
    if "amplitude" not in envelopes:
        raise FormatError(f"{path.name} has no amplitude envelope")
    amplitude = _breakpoints(envelopes["amplitude"], "amplitude", path.name)
    if len(amplitude) < 2:
        count = "is empty" if not amplitude else "has one breakpoint"
        raise FormatError(
            f"{path.name}: the amplitude envelope {count}; it needs at least two to last any time"
        )
    first, last = amplitude[0]["time"], amplitude[-1]["time"]
    if last <= first:
        raise FormatError(
            f"{path.name}: the amplitude envelope lasts zero seconds "
            f"(every breakpoint is at {first:g} s)"
        )
    notes: list[str] = []
    frequency = envelopes.get("frequency")
    if frequency is None:
        frequency = []
        notes.append(f"no frequency envelope: frequency {DEFAULT_FREQUENCY} assumed")
    else:
        frequency = _breakpoints(frequency, "frequency", path.name)
    outside = [b["time"] for b in frequency if not first <= b["time"] <= last]
    if outside:
        notes.append(
            f"{len(outside)} frequency breakpoint(s) lie outside the amplitude envelope "
            f"({first:g}-{last:g} s), which Meta's validator rejects"
        )
    emphasis = []
    for b in amplitude:
        if "emphasis" in b:
            level, freq = b["emphasis"]
            if level < b["value"]:
                notes.append(
                    f"the emphasis at {b['time']:g} s ({level:g}) is weaker than its breakpoint "
                    f"({b['value']:g}); it is written back at the breakpoint's level"
                )
            emphasis.append(Emphasis(b["time"], level, freq))
    design = VibrationDesign(
        tuple((b["time"], b["value"]) for b in amplitude),
        tuple((b["time"], b["value"]) for b in frequency),
        tuple(emphasis),
        max(last, *(b["time"] for b in frequency)) if frequency else last,
    )
    return design, notes, _convention(doc)


LINEAR_NOTE = "AHAP sharpness = frequency"  # metadata.description of a design read from Apple's


def _convention(doc: dict[str, Any]) -> str:
    """The AHAP sharpness convention a design keeps: "linear" where we wrote LINEAR_NOTE (a
    design that came from an Apple-made AHAP), else Meta's "sqrt"."""
    meta = doc.get("metadata")
    ours = isinstance(meta, dict) and meta.get("editor") == "haptic-timeline"
    return "linear" if ours and meta.get("description") == LINEAR_NOTE else "sqrt"


def design_document(design: VibrationDesign, convention: str = "sqrt") -> dict[str, Any]:
    """A v1 .haptic document for a design (emphasis on amplitude breakpoints at their times);
    a design in Apple's sharpness convention says so in its metadata, so an AHAP written from
    the file again keeps it."""
    amplitude = [{"time": t, "amplitude": v} for t, v in design.amplitude]
    if len(amplitude) < 2 or amplitude[-1]["time"] <= amplitude[0]["time"]:
        # Meta refuses an envelope of fewer than two breakpoints or no length: a silent one
        # spanning the design stands in, keeping the emphasis and frequency envelope.
        amplitude = [{"time": 0.0, "amplitude": 0.0}, {"time": design.duration, "amplitude": 0.0}]
    envelopes: dict[str, Any] = {"amplitude": _with_emphasis(amplitude, design.emphasis)}
    if design.frequency:
        envelopes["frequency"] = [{"time": t, "frequency": v} for t, v in design.frequency]
    return {
        "version": {"major": 1, "minor": 0, "patch": 0},
        "metadata": {
            "editor": "haptic-timeline",
            "author": "",
            "source": "",
            "project": "",
            "tags": [],
            "description": LINEAR_NOTE if convention == "linear" else "",
        },
        "signals": {"continuous": {"envelopes": envelopes}},
    }


def _with_emphasis(
    amplitude: list[dict[str, Any]], emphasis: tuple[Emphasis, ...]
) -> list[dict[str, Any]]:
    """The amplitude breakpoints with each emphasis (in time order) on a free one at its time.

    One walk through both, O(breakpoints + emphasis): an emphasis takes the first breakpoint at
    its time that carries none; when none is free, a breakpoint is added after those at its
    time, at their level, at the envelope's level between its neighbours (the one before may be
    an added one), or silent past the envelope's end. Its level is raised to the breakpoint's,
    as Meta's validator requires.
    """
    out: list[dict[str, Any]] = []
    free: deque[dict[str, Any]] = deque()
    i, n = 0, len(amplitude)
    current = None
    for e in emphasis:
        if e.time != current:
            current = e.time
            free.clear()
            while i < n and amplitude[i]["time"] <= e.time:
                out.append(amplitude[i])
                if amplitude[i]["time"] == e.time:
                    free.append(amplitude[i])
                i += 1
        if free:
            bp = free.popleft()
        else:
            level = _level_for(e.time, out, amplitude[i : i + 1], amplitude[0]["time"])
            bp = {"time": e.time, "amplitude": level}
            out.append(bp)
        bp["emphasis"] = {"amplitude": max(e.amplitude, bp["amplitude"]), "frequency": e.frequency}
    return _silent_until_start(out + amplitude[i:], amplitude[0])


def _silent_until_start(
    points: list[dict[str, Any]], first: dict[str, Any]
) -> list[dict[str, Any]]:
    """Where emphasis were added before the envelope's first breakpoint, a silent breakpoint at
    its time too, so the envelope steps up there instead of ramping from the added ones."""
    k = next(j for j, bp in enumerate(points) if bp is first)
    if k == 0 or first["amplitude"] == 0.0:
        return points
    return points[:k] + [{"time": first["time"], "amplitude": 0.0}] + points[k:]


def _level_for(
    time: float, before: list[dict[str, Any]], after: list[dict[str, Any]], start: float
) -> float:
    """The level of a breakpoint added at `time`: that of the last at its time, the envelope
    between the breakpoints around it, or 0 before the envelope's start and past its end."""
    if before and before[-1]["time"] == time:
        return before[-1]["amplitude"]
    if not after or time < start:
        return 0.0
    a, b = before[-1], after[0]
    return float(np.interp(time, [a["time"], b["time"]], [a["amplitude"], b["amplitude"]]))


class LofeltFormat:
    """Lofelt / Meta Haptics Studio .haptic: envelopes kept as a design, written back exactly."""

    name = "haptic"
    extensions = (".haptic",)
    reads = "design"
    writes = "project"
    options: tuple[str, ...] = ()

    def read(self, path: Path, *, progress: Progress | None = None, **options: Any) -> Imported:
        """The file's envelopes and emphasis as one vibration design on a drive track."""
        path = Path(path)
        design, notes, convention = read_with_convention(path)
        if progress is not None:
            progress(1.0)
        return design_placements(design, path.stem, str(path), convention, tuple(notes))

    def write(self, source: Project, path: Path, rate: float | None = None, **options: Any) -> None:
        """Write the project's sounding drive tracks as a v1 .haptic file."""
        convention = sharpness_convention(source)
        vib.write_json(design_document(design_of(source, rate=rate), convention), path)


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
