"""Readable, unique names for new tiles ("sine copy", "sine copy 2") and ranges named in the
project's display units ("four detents 20-260 deg", not radians)."""

from __future__ import annotations

import math
from collections.abc import Iterable

from timeline.model import Project


def unique_name(base: str, taken: Iterable[str]) -> str:
    """`base` if it is free, else "base 2", "base 3", ...: the first one not taken."""
    used = set(taken)
    if base not in used:
        return base
    return next(f"{base} {i}" for i in range(2, len(used) + 3) if f"{base} {i}" not in used)


def unique_tile_name(project: Project, base: str) -> str:
    """A name no tile of the project has yet, from `base`."""
    return unique_name(base, (t.name for t in project.tiles.values()))


def display_unit(axis: str) -> str:
    """The unit a designer reads on this axis: s, or deg on a position axis (radians inside)."""
    return "s" if axis == "time" else "deg"


def displayed(x: float, axis: str) -> float:
    """An axis value (s or rad) as a designer reads it (s or deg)."""
    return x if axis == "time" else math.degrees(x)


def span_text(a: float, b: float, axis: str) -> str:
    """A range of the axis as a designer reads it: "0.25-0.5 s", or "20-260 deg" in a position
    project (radians shown as degrees, to four significant figures)."""
    return f"{displayed(a, axis):.4g}-{displayed(b, axis):.4g} {display_unit(axis)}"
