"""Tables for a knob's firmware: the rendered layers as a C header (.h) or JSON (.json).

An embedded knob (SimpleFOC- or SmartKnob-style: a BLDC motor, an encoder, a field-oriented
control loop) looks its torque, damping and mass up by angle, or its drive by time. Each layer
becomes one table of `count` values sampled every `step` (radians on the position axis, seconds on
the time axis) from `start`, in SI units (N*m, N*m*s/rad, kg*m^2); the firmware interpolates
between entries and holds the ends. With `fixed_point=True` each table is int16: value = count x
scale, with one scale per table chosen so its largest magnitude is 32767 counts. The layout is in
docs/formats.md.
"""

from __future__ import annotations

import json
import re
from pathlib import Path
from typing import Any

import numpy as np

from timeline.plugins.file_formats import FormatError, Layers

UNITS = {
    "torque": "N*m",
    "drive": "N*m",
    "stiffness": "N*m/rad",
    "damping": "N*m*s/rad",
    "mass": "kg*m^2",
}
INT16_MAX = 32767
MAX_ENTRIES = 1_000_000  # per table: beyond this it will not fit a microcontroller's flash
PER_LINE = 8


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
    """Firmware tables: writes the rendered layers as a C header or JSON, reads nothing."""

    name = "firmware"
    extensions = (".h", ".json")
    reads = ""
    writes = "layers"
    options: tuple[str, ...] = ()

    def read(self, path: Path, **options: Any) -> None:
        return None

    def write(self, source: Layers, path: Path, fixed_point: bool = False, **options: Any) -> None:
        """Write every layer as a table (float32, or int16 with a scale when fixed_point)."""
        path = Path(path)
        if not source.columns:
            raise FormatError("the project renders no layers to put in a firmware table")
        if source.length > MAX_ENTRIES:
            raise FormatError(
                f"{source.length:,} entries per table is more than a microcontroller holds; "
                f"export with a lower --rate"
            )
        tables = _tables(source, fixed_point)
        if path.suffix.lower() == ".json":
            path.write_text(json.dumps(_document(source, tables), indent=1) + "\n")
        else:
            name = identifier(Path(options.get("target", path)).stem)
            path.write_text(_header(source, tables, name))


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
        "tables": tables,
    }


def _c_float(value: float) -> str:
    text = repr(float(value))
    return (text if ("." in text or "e" in text) else text + ".0") + "f"


def _rows(items: list[str]) -> str:
    lines = [", ".join(items[i : i + PER_LINE]) for i in range(0, len(items), PER_LINE)]
    return ",\n".join("    " + line for line in lines)


def _header(source: Layers, tables: dict[str, dict[str, Any]], name: str) -> str:
    axis, unit = _axis(source)
    upper = name.upper()
    out = [
        f"/* Haptic tables written by haptic-timeline: {', '.join(tables)} over {axis}. */",
        f"/* value(i) at {axis} = {upper}_START + i * {upper}_STEP ({unit}); SI units. */",
        f"#ifndef {upper}_H",
        f"#define {upper}_H",
        "",
        "#include <stdint.h>",
        "",
        f"#define {upper}_COUNT {source.length}",
        f"#define {upper}_START {_c_float(source.start)} /* {unit} */",
        f"#define {upper}_STEP {_c_float(1.0 / source.rate)} /* {unit} */",
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
