"""Snapping a dragged position to clip edges and the ruler grid (Qt-free)."""

from __future__ import annotations

import math
from collections.abc import Iterable

from timeline.model import Project


def clip_edges(project: Project, exclude: Iterable[str] = ()) -> list[float]:
    """Every clip's start and end, except the clips being dragged, plus the origin."""
    skip = set(exclude)
    edges = [0.0]
    for track in project.tracks:
        for clip in track.clips:
            if clip.id not in skip:
                edges += [clip.start, clip.end]
    return edges


def snap(value: float, edges: Iterable[float], grid: float, tolerance: float) -> float:
    """The nearest clip edge within tolerance, else the nearest grid line within it, else value."""
    best = min(edges, key=lambda e: abs(e - value), default=None)
    if best is not None and abs(best - value) <= tolerance:
        return best
    if grid > 0:
        line = round(value / grid) * grid
        if abs(line - value) <= tolerance and math.isfinite(line):
            return line
    return value
