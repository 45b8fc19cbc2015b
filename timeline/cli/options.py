"""Command-line options shared by several verbs."""

from __future__ import annotations

import argparse
import math

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
    p.add_argument("--rate", type=positive, help="output rate (default: the project's)")
    p.add_argument("--quality", choices=list(PRESETS), default=DEFAULT_QUALITY)
    p.add_argument("--start", type=number, default=0.0, help="start (s, or rad on position axis)")
    p.add_argument("--stop", type=number, help="stop (default: end of the last clip)")
    p.add_argument("--tracks", help="comma-separated track names or ids (default: all)")


def parse_tracks(text: str | None) -> list[str] | None:
    """Split a comma-separated --tracks value."""
    return None if text is None else [t.strip() for t in text.split(",") if t.strip()]
