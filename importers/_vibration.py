"""JSON plumbing shared by the vibration formats (.haptic, AHAP): bounded reads, checked numbers.

What the formats mean is in timeline.vibration (designs as envelope data) and in each format's
module; this holds only what both need to read and write their JSON safely.
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

from timeline.formats import FormatError

MAX_DURATION = 600.0  # s: longer designs are refused as hostile or broken
MAX_JSON_BYTES = 64 * 2**20


def load_json(path: Path, what: str) -> Any:
    """Parse a JSON file, or a FormatError naming the format."""
    raw = path.read_bytes()
    if len(raw) > MAX_JSON_BYTES:
        raise FormatError(f"{path.name} is too large to be an {what} file")
    try:
        return json.loads(raw.decode("utf-8-sig"))
    except (UnicodeDecodeError, ValueError, RecursionError):
        raise FormatError(f"{path.name} is not an {what} file (it is not valid JSON)") from None


def number(value: Any, where: str, lo: float = -math.inf, hi: float = math.inf) -> float:
    """A finite JSON number within [lo, hi], or a FormatError saying where."""
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise FormatError(f"{where} must be a number")
    try:
        value = float(value)
    except OverflowError:  # an integer literal beyond float range
        raise FormatError(f"{where} is too large (it must be between {lo:g} and {hi:g})") from None
    if not (math.isfinite(value) and lo <= value <= hi):
        raise FormatError(f"{where} must be between {lo:g} and {hi:g}, not {value:g}")
    return value


def write_json(doc: Any, path: Path) -> None:
    """Write a JSON document (no NaN or infinity) with two-space indentation."""
    Path(path).write_text(json.dumps(doc, indent=2, allow_nan=False) + "\n", encoding="utf-8")
