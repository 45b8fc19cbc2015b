"""Numbers on a project's axis as a person types and reads them on the command line.

A time project speaks seconds; a position project speaks degrees (its axis is radians inside).
A typed value may name its unit: "0.5s", "250ms", "90deg", "90°", "1.2rad"; a unit of the other
axis is refused with one sentence. A rate is samples per second, or per degree on a position
project, and may name its own unit: "10000/s", "1/deg", "5730/rad".
"""

from __future__ import annotations

import argparse
import math
from dataclasses import dataclass

from timeline.errors import HapticTimelineError

DEG_PER_RAD = 180.0 / math.pi
# unit written after a value -> (the axis it belongs to, axis units (s or rad) per one of it)
LENGTH_UNITS = {
    "ms": ("time", 1e-3),
    "s": ("time", 1.0),
    "deg": ("position", 1.0 / DEG_PER_RAD),
    "°": ("position", 1.0 / DEG_PER_RAD),
    "rad": ("position", 1.0),
}
RATE_UNITS = {
    "/s": ("time", 1.0),
    "hz": ("time", 1.0),
    "/deg": ("position", DEG_PER_RAD),
    "/rad": ("position", 1.0),
}
SPOKEN = {"time": "seconds (0.5 or 0.5s)", "position": "degrees (90 or 90deg) or radians (1.5rad)"}


@dataclass(frozen=True)
class Typed:
    """A finite number as typed, with the unit written after it (None: the axis's own)."""

    value: float
    unit: str | None
    text: str


def _typed(text: str, units: dict[str, tuple[str, float]]) -> Typed:
    """Split "90deg" into 90.0 and "deg" (argparse's one-line error when it is not a number)."""
    body = text.strip()
    unit = next((u for u in sorted(units, key=len, reverse=True) if body.lower().endswith(u)), None)
    number = body[: len(body) - len(unit)].strip() if unit else body
    try:
        value = float(number)
    except ValueError:
        names = ", ".join(units)
        raise argparse.ArgumentTypeError(
            f"{text!r} is not a number (a unit, if any, goes after it: {names})"
        ) from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"{text!r} is not a finite number")
    return Typed(value, unit, text)


def axis_value(text: str) -> Typed:
    """An argparse type: a place or a length on the axis, maybe with its unit."""
    return _typed(text, LENGTH_UNITS)


def positive_axis_value(text: str) -> Typed:
    """An argparse type: a length above zero on the axis, maybe with its unit."""
    typed = axis_value(text)
    if typed.value <= 0:
        raise argparse.ArgumentTypeError(f"{text!r} must be above zero")
    return typed


def axis_rate(text: str) -> Typed:
    """An argparse type: a sample rate above zero, maybe with its unit ("1/deg")."""
    typed = _typed(text, RATE_UNITS)
    if typed.value <= 0:
        raise argparse.ArgumentTypeError(f"{text!r} must be above zero")
    return typed


def _resolve(typed: Typed, axis: str, option: str, units: dict, own: float, owner: str) -> float:
    if typed.unit is None:
        return typed.value * own
    unit_axis, factor = units[typed.unit]
    if unit_axis != axis:
        kinds = {"time": "a time", "position": "an angle"}
        raise HapticTimelineError(
            f"{option} {typed.text} is {kinds[unit_axis]}, but {owner} is {kinds[axis]}: give "
            f"{SPOKEN[axis]}"
        )
    return typed.value * factor


def on_axis(typed: Typed, axis: str, option: str, owner: str = "the project's axis") -> float:
    """A typed place or length in axis units: seconds, or radians (typed in degrees)."""
    own = 1.0 if axis == "time" else 1.0 / DEG_PER_RAD
    return _resolve(typed, axis, option, LENGTH_UNITS, own, owner)


def rate_on_axis(typed: Typed, axis: str, option: str = "--rate") -> float:
    """A typed rate in samples per axis unit (per second, or per radian: typed per degree)."""
    own = 1.0 if axis == "time" else DEG_PER_RAD
    return _resolve(typed, axis, option, RATE_UNITS, own, "the project's axis")


def amount(x: float, axis: str) -> str:
    """An axis value with its unit, to six significant figures: "0.25 s", "280 deg"."""
    from timeline.edits.naming import display_unit, displayed  # after the project (numpy) loads

    return f"{displayed(x, axis):.6g} {display_unit(axis)}"


def rate_text(rate: float, axis: str) -> str:
    """A sample rate as typed: "10000/s", or "100/deg" on a position axis."""
    if axis == "time":
        return f"{rate:g}/s"
    return f"{rate / DEG_PER_RAD:g}/deg"
