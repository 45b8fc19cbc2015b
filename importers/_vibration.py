"""JSON plumbing shared by the vibration formats (.haptic, AHAP): bounded reads, checked numbers.

What the formats mean is in timeline.edits.vibration (designs as envelope data) and in each format's
module; this holds only what both need to read and write their JSON safely.
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

from importers._bounded_read import read_at_most
from timeline.plugins.file_formats import FormatError

MAX_DURATION = 600.0  # s: longer designs are refused as hostile or broken
MAX_JSON_BYTES = 64 * 2**20


def load_json(path: Path, what: str) -> Any:
    """Parse a JSON file, or a FormatError naming the format."""
    return parse_json(json_text(path, what), path.name, what)


def json_text(path: Path, what: str) -> str:
    """A JSON file's text, or a FormatError: larger than MAX_JSON_BYTES (judged by its size
    before anything is read) or not UTF-8."""
    path = Path(path)
    too_large = FormatError(
        f"{path.name} is larger than {MAX_JSON_BYTES // 2**20} MB, the most an {what} file may be"
    )
    raw = read_at_most(path, MAX_JSON_BYTES, too_large)
    try:
        return raw.decode("utf-8-sig")
    except UnicodeDecodeError:
        raise _not_json(path.name, what) from None


def parse_json(text: str, name: str, what: str, **hooks: Any) -> Any:
    """json.loads(text, **hooks), or a FormatError saying the file is not JSON."""
    try:
        return json.loads(text, **hooks)
    except (ValueError, RecursionError):
        raise _not_json(name, what) from None


def _not_json(name: str, what: str) -> FormatError:
    return FormatError(f"{name} is not an {what} file (it is not valid JSON)")


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
