"""Tables for a knob's firmware: the rendered layers as a C header (.h) or JSON (.json).

An embedded knob (SimpleFOC- or SmartKnob-style: a BLDC motor, an encoder, a field-oriented
control loop; the reference firmware's position mode, docs/firmware.md) looks its torque, damping
and mass up by angle, or its drive by time. Each layer becomes one table of `count` values
sampled every `step` (radians on the position axis, seconds on the time axis) from `start`, in SI
units (N*m, N*m*s/rad, kg*m^2); the firmware interpolates between entries and holds the ends.

The tables cover the whole axis end to end: entry 0 at the start, the last entry at the axis end
(its value just inside it, where the clips end), so a 280 degree axis at one entry per degree has
281 entries. The default step suits a microcontroller: one entry per degree on the position axis,
one per millisecond on the time axis, and never more than `MAX_DEFAULT_INTERVALS` steps (a longer
axis gets a coarser step: at most 16,385 entries, 64 KiB a float32 table); `rate` (entries per
radian or per second) asks for another step, rounded so the entries still land on both ends.
The header's comment and `summary` say the size. With `fixed_point=True` each table is int16:
value = count x scale, with one scale per table chosen so its largest magnitude is 32767 counts.
The layout is in docs/formats.md.
"""

from __future__ import annotations

import json
import math
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from timeline.model import Project
from timeline.plugins.file_formats import FormatError, Layers

UNITS = {
    "torque": "N*m",
    "drive": "N*m",
    "stiffness": "N*m/rad",
    "damping": "N*m*s/rad",
    "mass": "kg*m^2",
}
INT16_MAX = 32767
FLOAT32_MAX = float(np.finfo(np.float32).max)
MAX_ENTRIES = 1_000_000  # per table: beyond this it will not fit a microcontroller's flash
PER_LINE = 8
DEFAULT_PER_UNIT = {"position": 180.0 / math.pi, "time": 1000.0}  # 1 per degree, 1 per ms
MAX_DEFAULT_INTERVALS = 16_384  # a default table has at most this many steps (+1 entries)
END_INSIDE = 1e-6  # the last entry is read this fraction of a step inside the axis end


@dataclass(frozen=True)
class Grid:
    """Where a table's entries sit: `count` of them every `step` from `start` to the end."""

    start: float
    step: float
    count: int
    axis: str

    @property
    def stop(self) -> float:
        return self.start + self.step * (self.count - 1)

    def describe(self, tables: int, fixed_point: bool = False) -> str:
        """One line: entries, step, span and bytes (what the CLI prints, the header states)."""
        size = 2 if fixed_point else 4
        if self.axis == "position":
            where = f"every {math.degrees(self.step):.6g} deg from {math.degrees(self.start):g} "
            where += f"to {math.degrees(self.stop):.6g} deg"
        else:
            where = f"every {self.step * 1e3:.6g} ms from {self.start:g} to {self.stop:.6g} s"
        return (
            f"{tables} table(s) x {self.count:,} entries ({where}), "
            f"{tables * self.count * size:,} bytes of {'int16' if fixed_point else 'float32'}"
        )


def grid(project: Project, rate: float | None = None) -> Grid:
    """The entries of a project's tables: the default rule, or `rate` per axis unit rounded so
    that both ends of the axis are entries."""
    span = project.duration
    if not span > 0:
        raise FormatError("the project has no clips to export")
    per_unit = rate or DEFAULT_PER_UNIT[project.axis]
    if not (math.isfinite(per_unit) and per_unit > 0):
        raise FormatError(f"a table's rate must be a positive number, not {per_unit}")
    # a span of 1e307 s at 1000 per s is no count at all: past MAX_ENTRIES is as good as infinite
    steps = max(1, math.ceil(min(span * per_unit - 1e-6, 2.0 * MAX_ENTRIES)))
    if rate is None:
        steps = min(steps, MAX_DEFAULT_INTERVALS)
    if steps + 1 > MAX_ENTRIES:
        raise FormatError(
            f"{steps + 1:,} entries per table is more than a microcontroller holds; "
            "export with a lower --rate"
        )
    return Grid(0.0, span / steps, steps + 1, project.axis)


def render_tables(project: Project, table_grid: Grid) -> Layers:
    """The project's layers at the grid's entries (the last one just inside the axis end)."""
    from timeline.rendering.mixer import render

    n = table_grid.count - 1
    step = table_grid.step
    body = render(project, table_grid.start, table_grid.start + n * step, 1.0 / step)
    end = table_grid.stop - END_INSIDE * step
    last = render(project, end, end + step, 1.0 / step)
    if not body:
        raise FormatError("every track with clips is muted, so there is nothing to export")
    columns = {
        name: np.concatenate([np.asarray(values)[:n], np.asarray(last[name])[:1]])
        for name, values in body.items()
    }
    return Layers(columns, 1.0 / step, table_grid.start, project.axis)


def identifier(text: str) -> str:
    """A C identifier made from a name: letters, digits, underscores; never a leading digit."""
    name = re.sub(r"[^0-9A-Za-z_]+", "_", text).strip("_").lower() or "haptic"
    return f"t_{name}" if name[0].isdigit() else name


def quantised(values: np.ndarray) -> tuple[np.ndarray, float]:
    """int16 counts and the scale (SI units per count) that maps the largest magnitude to 32767."""
    peak = float(np.max(np.abs(values))) if len(values) else 0.0
    scale = peak / INT16_MAX if peak > 0 else 1.0
    return np.round(values / scale).astype(np.int16), scale


class FirmwareFormat:
    """Firmware tables: renders a project on the tables' grid (or takes rendered layers, a
    tile's) and writes it as a C header or JSON; reads nothing."""

    name = "firmware"
    extensions = (".h", ".json")
    reads = ""
    writes = "project"
    options: tuple[str, ...] = ()

    def read(self, path: Path, **options: Any) -> None:
        return None

    @staticmethod
    def grid(project: Project, rate: float | None = None) -> Grid:
        """Where the tables' entries sit (the export dialog shows it before writing)."""
        return grid(project, rate)

    def write(
        self,
        source: Project | Layers,
        path: Path,
        fixed_point: bool = False,
        rate: float | None = None,
        **options: Any,
    ) -> str:
        """Write every layer as a table (float32, or int16 with a scale when fixed_point);
        returns the one line that says its size."""
        path = Path(path)
        if isinstance(source, Project):
            source = render_tables(source, grid(source, rate))
        if not source.columns:
            raise FormatError("the project renders no layers to put in a firmware table")
        if source.length > MAX_ENTRIES:
            raise FormatError(
                f"{source.length:,} entries per table is more than a microcontroller holds; "
                f"export with a lower --rate"
            )
        tables = _tables(source, fixed_point)
        size = Grid(source.start, 1.0 / source.rate, source.length, source.axis)
        summary = size.describe(len(tables), fixed_point)
        if path.suffix.lower() == ".json":
            path.write_text(json.dumps(_document(source, tables), indent=1) + "\n")
        else:
            name = identifier(Path(options.get("target", path)).stem)
            path.write_text(_header(source, tables, name, summary))
        return summary


def _tables(source: Layers, fixed_point: bool) -> dict[str, dict[str, Any]]:
    out = {}
    for name, values in source.columns.items():
        values = np.asarray(values, dtype=np.float64)
        if not np.isfinite(values).all():
            raise FormatError(f"the {name} layer holds a value that is not a finite number")
        entry: dict[str, Any] = {"unit": UNITS.get(name, "")}
        if fixed_point:
            counts, scale = quantised(values)
            entry.update(type="int16", scale=scale, values=counts.tolist())
        else:
            peak = float(np.abs(values).max(initial=0.0))
            if peak > FLOAT32_MAX:
                raise FormatError(
                    f"the {name} layer reaches {peak:.3g}, beyond the largest float32 "
                    f"({FLOAT32_MAX:.3g}); export it with --fixed-point, or scale it down"
                )
            entry.update(type="float32", values=values.astype(np.float32).tolist())
        out[name] = entry
    return out


def _axis(source: Layers) -> tuple[str, str]:
    return ("position", "rad") if source.axis == "position" else ("time", "s")


def _document(source: Layers, tables: dict[str, dict[str, Any]]) -> dict[str, Any]:
    axis, unit = _axis(source)
    return {
        "format": "haptic-timeline firmware tables",
        "version": 1,
        "axis": axis,
        "axis_unit": unit,
        "start": source.start,
        "step": 1.0 / source.rate,
        "count": source.length,
        "rate": source.rate,
        "tables": tables,
    }


def _c_float(value: float) -> str:
    text = repr(float(value))
    return (text if ("." in text or "e" in text) else text + ".0") + "f"


def _rows(items: list[str]) -> str:
    lines = [", ".join(items[i : i + PER_LINE]) for i in range(0, len(items), PER_LINE)]
    return ",\n".join("    " + line for line in lines)


def _header(source: Layers, tables: dict[str, dict[str, Any]], name: str, summary: str) -> str:
    axis, unit = _axis(source)
    upper = name.upper()
    per = "entries per radian" if axis == "position" else "entries per second"
    out = [
        f"/* Haptic tables written by haptic-timeline: {', '.join(tables)} over {axis}. */",
        f"/* value(i) at {axis} = {upper}_START + i * {upper}_STEP, in {unit} (radians, not "
        "degrees, on the position axis); i = 0 .. COUNT - 1, the last entry at the axis end. */"
        if axis == "position"
        else f"/* value(i) at {axis} = {upper}_START + i * {upper}_STEP, in {unit}; i = 0 .. "
        "COUNT - 1, the last entry at the axis end. */",
        "/* Values in SI units (below); between entries interpolate, beyond the ends hold. */",
        f"/* Size: {summary}. */",
        f"#ifndef {upper}_H",
        f"#define {upper}_H",
        "",
        "#include <stdint.h>",
        "",
        f"#define {upper}_COUNT {source.length}",
        f"#define {upper}_START {_c_float(source.start)} /* {unit} */",
        f"#define {upper}_STEP {_c_float(1.0 / source.rate)} /* {unit} */",
        f"#define {upper}_RATE {float(source.rate)!r} /* {per}: 1 / STEP in double */",
        "",
    ]
    for layer, table in tables.items():
        symbol = f"{name}_{identifier(layer)}"
        if table["type"] == "int16":
            out.append(
                f"#define {symbol.upper()}_SCALE {_c_float(table['scale'])}"
                f" /* {table['unit']} per count */"
            )
            items = [str(v) for v in table["values"]]
            declaration = f"static const int16_t {symbol}[{upper}_COUNT]"
        else:
            items = [_c_float(v) for v in table["values"]]
            declaration = f"static const float {symbol}[{upper}_COUNT]"
        out += [f"{declaration} = {{ /* {table['unit']} */", _rows(items), "};", ""]
    out += [f"#endif /* {upper}_H */", ""]
    return "\n".join(out)


FORMAT = FirmwareFormat()
