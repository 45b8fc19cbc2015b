"""Edits of markers and the loop region: pure functions like the other edits.

Markers are kept sorted by position; the loop region is a half-open range [start, stop) or None.
"""

from __future__ import annotations

from dataclasses import replace

from timeline.errors import EditError, finite
from timeline.model import Project
from timeline.model.markers import LoopRegion, Marker


def _sorted(markers) -> tuple[Marker, ...]:
    return tuple(sorted(markers, key=lambda m: m.at))


def next_marker_name(project: Project) -> str:
    """The first free name of the form "M1", "M2", ..."""
    taken = {m.name for m in project.markers}
    return next(f"M{i}" for i in range(1, len(taken) + 2) if f"M{i}" not in taken)


def add_marker(project: Project, at: float, name: str | None = None) -> tuple[Project, int]:
    """Add a marker (a free name "Mn" unless named); returns its index in the sorted markers."""
    marker = Marker(name or next_marker_name(project), max(0.0, finite("a marker", at)))
    markers = _sorted((*project.markers, marker))
    return replace(project, markers=markers), markers.index(marker)


def add_markers(project: Project, markers: tuple[Marker, ...]) -> Project:
    """Add named markers at once (an import's), kept sorted with the project's own."""
    return replace(project, markers=_sorted((*project.markers, *markers)))


def move_marker(project: Project, index: int, at: float) -> Project:
    """Move the marker at an index to another place."""
    marker = _marker(project, index)
    rest = [m for i, m in enumerate(project.markers) if i != index]
    moved = replace(marker, at=max(0.0, finite("a marker", at)))
    return replace(project, markers=_sorted((*rest, moved)))


def rename_marker(project: Project, index: int, name: str) -> Project:
    """Give the marker at an index another name."""
    marker = _marker(project, index)
    markers = list(project.markers)
    markers[index] = replace(marker, name=name.strip())
    return replace(project, markers=tuple(markers))


def remove_marker(project: Project, index: int) -> Project:
    """Remove the marker at an index."""
    _marker(project, index)
    return replace(project, markers=project.markers[:index] + project.markers[index + 1 :])


def set_loop(project: Project, start: float | None, stop: float | None = None) -> Project:
    """Loop playback over [start, stop), in either order; None (or no length) clears it."""
    if start is None or stop is None or start == stop:
        return replace(project, loop=None)
    a, b = sorted((max(0.0, start), max(0.0, stop)))
    return replace(project, loop=LoopRegion(a, b) if b > a else None)


def _marker(project: Project, index: int) -> Marker:
    if not 0 <= index < len(project.markers):
        raise EditError(f"there is no marker {index + 1}")
    return project.markers[index]
