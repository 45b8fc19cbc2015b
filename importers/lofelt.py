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

import json
from collections import deque
from collections.abc import Iterator, Sequence
from itertools import islice
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
from timeline.errors import ControlFlow
from timeline.model import Project
from timeline.plugins.file_formats import FormatError, Imported, Progress
from timeline.signal.vibration_design import DEFAULT_FREQUENCY

MAX_WEAK_NOTES = 3  # weak emphases noted one by one; past these, one note counts the rest


class _Unusual(ControlFlow):
    """A breakpoint the fast path does not take: the checked path says what is wrong."""


def _breakpoints(items: Any, key: str, where: str) -> _Envelope:
    """An envelope's breakpoints, each checked (times in 0..MAX_DURATION and never going back,
    values and emphasis in 0..1), or a FormatError naming the first that is not.

    One pass over plain dicts of floats (what every tool writes) with no text built per
    breakpoint; anything else is read again by the checked path, for its sentence.
    """
    if not isinstance(items, list):
        raise FormatError(f"{where}: the {key} envelope must be a list of breakpoints")
    try:
        return _fast(items, key)
    except (_Unusual, KeyError, TypeError, OverflowError):
        return _checked(items, key, where)


class _Envelope:
    """An envelope read: breakpoint times and values, and emphasis as (index, amp, frequency)."""

    __slots__ = ("emphasis", "times", "values")

    def __init__(self) -> None:
        self.times: list[float] = []
        self.values: list[float] = []
        self.emphasis: list[tuple[int, float, float]] = []


def _unit(value: Any, hi: float = 1.0) -> float:
    """A plain JSON number within 0..hi as a float, else _Unusual."""
    kind = type(value)
    if kind is int:
        value = float(value)
    elif kind is not float:
        raise _Unusual
    if not 0.0 <= value <= hi:  # NaN fails too
        raise _Unusual
    return value


def _fast(items: list[Any], key: str) -> _Envelope:
    out = _Envelope()
    times, values, emphasis = out.times, out.values, out.emphasis
    previous = 0.0
    longest = vib.MAX_DURATION
    for k, bp in enumerate(items):
        if type(bp) is not dict:
            raise _Unusual
        time = _unit(bp["time"], longest)
        if time < previous:
            raise _Unusual
        previous = time
        times.append(time)
        values.append(_unit(bp[key]))
        e = bp.get("emphasis")
        if e is not None:
            if type(e) is not dict:
                raise _Unusual
            emphasis.append((k, _unit(e["amplitude"]), _unit(e["frequency"])))
    return out


def _checked(items: list[Any], key: str, where: str) -> _Envelope:
    """_fast with a sentence for the first breakpoint that is not valid."""
    out = _Envelope()
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
        out.times.append(time)
        out.values.append(vib.number(bp[key], f"{here} {key}", 0.0, 1.0))
        emphasis = bp.get("emphasis")
        if emphasis is not None:
            if not isinstance(emphasis, dict):
                raise FormatError(f"{here} emphasis must be an object")
            for field in ("amplitude", "frequency"):
                if field not in emphasis:
                    raise FormatError(f"{here} emphasis has no {field}")
            out.emphasis.append((
                k,
                vib.number(emphasis["amplitude"], f"{here} emphasis amplitude", 0.0, 1.0),
                vib.number(emphasis["frequency"], f"{here} emphasis frequency", 0.0, 1.0),
            ))  # fmt: skip
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
    frequency_items = envelopes.get("frequency")
    frequency = (
        None if frequency_items is None
        else _breakpoints(frequency_items, "frequency", path.name)
    )  # fmt: skip
    convention = _convention(doc)
    del doc, envelopes, frequency_items  # the parsed JSON goes before the design is built
    if len(amplitude.times) < 2:
        count = "is empty" if not amplitude.times else "has one breakpoint"
        raise FormatError(
            f"{path.name}: the amplitude envelope {count}; it needs at least two to last any time"
        )
    first, last = amplitude.times[0], amplitude.times[-1]
    if last <= first:
        raise FormatError(
            f"{path.name}: the amplitude envelope lasts zero seconds "
            f"(every breakpoint is at {first:g} s)"
        )
    notes: list[str] = []
    if frequency is None:
        frequency = _Envelope()
        notes.append(f"no frequency envelope: frequency {DEFAULT_FREQUENCY} assumed")
    outside = sum(1 for t in frequency.times if not first <= t <= last)
    if outside:
        notes.append(
            f"{outside} frequency breakpoint(s) lie outside the amplitude envelope "
            f"({first:g}-{last:g} s), which Meta's validator rejects"
        )
    notes += _weak_notes(amplitude)
    times = amplitude.times
    design = VibrationDesign(
        tuple(zip(times, amplitude.values, strict=True)),
        tuple(zip(frequency.times, frequency.values, strict=True)),
        tuple(Emphasis(times[k], level, freq) for k, level, freq in amplitude.emphasis),
        max(last, *frequency.times) if frequency.times else last,
    )
    return design, notes, convention


LINEAR_NOTE = "AHAP sharpness = frequency"  # metadata.description of a design read from Apple's


def _convention(doc: dict[str, Any]) -> str:
    """The AHAP sharpness convention a design keeps: "linear" where we wrote LINEAR_NOTE (a
    design that came from an Apple-made AHAP), else Meta's "sqrt"."""
    meta = doc.get("metadata")
    ours = isinstance(meta, dict) and meta.get("editor") == "haptic-timeline"
    return "linear" if ours and meta.get("description") == LINEAR_NOTE else "sqrt"


def _weak_notes(amplitude: _Envelope) -> list[str]:
    """A note per emphasis weaker than its breakpoint (written back at the breakpoint's level),
    the first MAX_WEAK_NOTES of them, then one counting the rest."""
    times, values = amplitude.times, amplitude.values
    weak = [(k, level) for k, level, _ in amplitude.emphasis if level < values[k]]
    notes = [
        f"the emphasis at {times[k]:g} s ({level:g}) is weaker than its breakpoint "
        f"({values[k]:g}); it is written back at the breakpoint's level"
        for k, level in weak[:MAX_WEAK_NOTES]
    ]
    if len(weak) > MAX_WEAK_NOTES:
        notes.append(
            f"{len(weak) - MAX_WEAK_NOTES:,} more emphases are weaker than their breakpoints; "
            "they are written back at the breakpoints' levels"
        )
    return notes


def design_document(design: VibrationDesign, convention: str = "sqrt") -> dict[str, Any]:
    """A v1 .haptic document for a design (emphasis on amplitude breakpoints at their times);
    a design in Apple's sharpness convention says so in its metadata, so an AHAP written from
    the file again keeps it."""
    doc = _skeleton(design, convention)
    envelopes = doc["signals"]["continuous"]["envelopes"]
    for name, points in _envelope_points(design).items():
        envelopes[name] = list(points)
    return doc


def write_design(design: VibrationDesign, path: Path, convention: str = "sqrt") -> None:
    """Write `design_document(design, convention)` as `vib.write_json` does, byte for byte,
    with the breakpoints formatted and written in chunks as they come: neither their dicts
    nor the whole text is held (864,000 breakpoints for a 2-hour sound)."""
    doc = _skeleton(design, convention)
    points = _envelope_points(design)
    doc["signals"]["continuous"]["envelopes"] = {name: _MARK + name for name in points}
    text = json.dumps(doc, indent=2, allow_nan=False) + "\n"
    with Path(path).open("w", encoding="utf-8") as file:
        for name, items in points.items():
            mark = json.dumps(_MARK + name)
            head, text = text.split(mark, 1)
            file.write(head)
            pad = " " * (len(head) - head.rindex("\n") - 1 - len(json.dumps(name)) - 2)
            _write_list(file, items, pad)
        file.write(text)


_MARK = "\x00breakpoints of "  # stands for an envelope's list in the skeleton's text
_CHUNK = 4096  # breakpoints formatted per write
_ENCODER = json.JSONEncoder(indent=2, allow_nan=False)  # what json.dumps(indent=2, ...) uses


def _write_list(file: Any, items: Iterator[dict[str, Any]], pad: str) -> None:
    """A non-empty list of breakpoints as json.dumps(indent=2) writes it at indentation `pad`:
    each chunk encoded as a list of its own, its lines indented by `pad`."""
    file.write("[\n")
    separator = ""
    for chunk in iter(lambda: list(islice(items, _CHUNK)), []):
        text = _ENCODER.encode(chunk)  # "[\n  {...},\n  {...}\n]"
        file.write(separator + pad + text[2:-2].replace("\n", "\n" + pad))
        separator = ",\n"
    file.write("\n" + pad + "]")


def _skeleton(design: VibrationDesign, convention: str) -> dict[str, Any]:
    """The document without its envelopes (an empty dict stands for them)."""
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
        "signals": {"continuous": {"envelopes": {}}},
    }


def _envelope_points(design: VibrationDesign) -> dict[str, Iterator[dict[str, Any]]]:
    """Each envelope's breakpoints as they come, amplitude (never empty) first."""
    amplitude = design.amplitude
    if len(amplitude) < 2 or amplitude[-1][0] <= amplitude[0][0]:
        # Meta refuses an envelope of fewer than two breakpoints or no length: a silent one
        # spanning the design stands in, keeping the emphasis and frequency envelope.
        amplitude = ((0.0, 0.0), (design.duration, 0.0))
    points = {"amplitude": _with_emphasis(amplitude, design.emphasis)}
    if design.frequency:
        points["frequency"] = ({"time": t, "frequency": v} for t, v in design.frequency)
    return points


def _with_emphasis(
    amplitude: Sequence[tuple[float, float]], emphasis: tuple[Emphasis, ...]
) -> Iterator[dict[str, Any]]:
    """The amplitude breakpoints with each emphasis (in time order) on a free one at its time.

    One walk through both, O(breakpoints + emphasis): an emphasis takes the first breakpoint at
    its time that carries none; when none is free, a breakpoint is added after those at its
    time, at their level, at the envelope's level between its neighbours (the one before may be
    an added one), or silent past the envelope's end. Its level is raised to the breakpoint's,
    as Meta's validator requires. The breakpoints at an emphasis' time are held until the next
    emphasis' time; where emphasis were added before the envelope's first breakpoint, a silent
    breakpoint at its time comes before it, so the envelope steps up there instead of ramping
    from the added ones.
    """
    start, first_level = amplitude[0]
    held: list[tuple[dict[str, Any], int]] = []  # at the current emphasis' time, with their index
    free: deque[dict[str, Any]] = deque()
    last: dict[str, Any] | None = None  # the last breakpoint given out or held
    i, n = 0, len(amplitude)
    current = None
    before_start = False  # breakpoints were added before the envelope's first one

    def given(bp: dict[str, Any], original: int) -> Iterator[dict[str, Any]]:
        if original == 0 and before_start and first_level != 0.0:
            yield {"time": start, "amplitude": 0.0}
        yield bp

    for e in emphasis:
        if e.time != current:
            current = e.time
            for bp, original in held:
                yield from given(bp, original)
            held = []
            free.clear()
            while i < n and (point := amplitude[i])[0] <= e.time:
                bp = {"time": point[0], "amplitude": point[1]}
                if point[0] == e.time:
                    free.append(bp)
                    held.append((bp, i))
                else:
                    yield from given(bp, i)
                last = bp
                i += 1
        if free:
            bp = free.popleft()
        else:
            bp = {
                "time": e.time,
                "amplitude": _level_for(e.time, last, amplitude[i : i + 1], start),
            }
            before_start = before_start or i == 0
            held.append((bp, -1))
            last = bp
        bp["emphasis"] = {"amplitude": max(e.amplitude, bp["amplitude"]), "frequency": e.frequency}
    for bp, original in held:
        yield from given(bp, original)
    for j, (t, v) in enumerate(amplitude[i:], i):  # Breakpoints iterate a chunk at a time
        yield from given({"time": t, "amplitude": v}, j)


def _level_for(
    time: float,
    before: dict[str, Any] | None,
    after: Sequence[tuple[float, float]],
    start: float,
) -> float:
    """The level of a breakpoint added at `time`: that of the last at its time, the envelope
    between the breakpoints around it, or 0 before the envelope's start and past its end."""
    if before is not None and before["time"] == time:
        return before["amplitude"]
    if not after or time < start or before is None:
        return 0.0
    (t_b, v_b) = after[0]
    return float(np.interp(time, [before["time"], t_b], [before["amplitude"], v_b]))


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
        write_design(design_of(source, rate=rate), path, convention)


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
