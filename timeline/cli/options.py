"""Command-line options shared by several verbs."""

from __future__ import annotations

import argparse
import math

from timeline.cli.units import axis_rate, axis_value
from timeline.signal.render_presets import DEFAULT_QUALITY, PRESETS


def number(text: str) -> float:
    """A finite number, or argparse's one-line error."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"{text!r} is not a finite number")
    return value


def positive(text: str) -> float:
    """A finite number above zero."""
    value = number(text)
    if value <= 0:
        raise argparse.ArgumentTypeError(f"{text!r} must be above zero")
    return value


def add_range_options(p: argparse.ArgumentParser) -> None:
    """--rate, --quality, --start, --stop and --tracks."""
    p.add_argument("--rate", type=axis_rate, help="output rate: samples per second, or per "
                   "radian on a position project; 1/deg also (default: the project's)")  # fmt: skip
    p.add_argument("--quality", choices=list(PRESETS), default=DEFAULT_QUALITY)
    p.add_argument("--start", type=axis_value, help="start: seconds, or degrees on a position "
                   "project; 0.5s, 90deg, 1.2rad also (default: 0)")  # fmt: skip
    p.add_argument("--stop", type=axis_value, help="stop, as --start (default: the project's end)")
    p.add_argument("--tracks", help="comma-separated track names or ids (default: all)")


def parse_tracks(text: str | None) -> list[str] | None:
    """Split a comma-separated --tracks value."""
    return None if text is None else [t.strip() for t in text.split(",") if t.strip()]
