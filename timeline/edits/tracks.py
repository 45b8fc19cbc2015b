"""A new project and the edits of its tracks: add, remove, set (name, gain, mute, solo), move.

Pure functions like every edit: bad input raises EditError and nothing has changed; functions
that create something return (project, new_id).
"""

from __future__ import annotations

import math
from dataclasses import replace
from types import MappingProxyType
from typing import Any

from timeline.edits.palette import add_tile
from timeline.errors import EditError
from timeline.model import (
    DEFAULT_POSITION_RATE,
    DEFAULT_TIME_RATE,
    Project,
    Track,
)
from timeline.plugins.track_kinds import track_kind
from timeline.tiles.templates import template_tiles


def new_project(
    axis: str = "time", rate: float | None = None, templates: bool = True, **metadata: Any
) -> Project:
    """An empty project on the time axis (10 kHz) or the position axis (one sample per 0.01 deg).

    With templates, the Templates tab holds one tile of every generator.
    """
    if rate is None:
        rate = DEFAULT_TIME_RATE if axis == "time" else DEFAULT_POSITION_RATE
    project = Project(axis=axis, rate=rate, metadata=MappingProxyType(metadata))
    if templates:
        for tile in template_tiles(axis):
            project, _ = add_tile(project, tile, "Templates")
    return project


def add_track(
    project: Project, kind: str, name: str | None = None, **fields: Any
) -> tuple[Project, str]:
    """Add a track of a kind usable on the project's axis."""
    k = track_kind(kind)
    if project.axis not in k.axes:
        raise EditError(f"a {project.axis} project cannot have a {kind} track")
    project, track_id = project.with_id("t")
    count = sum(t.kind == kind for t in project.tracks) + 1
    track = Track(id=track_id, kind=kind, name=name or f"{k.label} {count}", **fields)
    return replace(project, tracks=project.tracks + (track,)), track_id


def remove_track(project: Project, track_id: str) -> Project:
    """Remove a track and its clips."""
    project.track(track_id)
    return replace(project, tracks=tuple(t for t in project.tracks if t.id != track_id))


def set_track(project: Project, track_id: str, **fields: Any) -> Project:
    """Change a track's name, gain, mute, solo or full scale."""
    allowed = {"name", "gain", "mute", "solo", "full_scale"}
    if set(fields) - allowed:
        raise EditError(f"a track has no setting {sorted(set(fields) - allowed)[0]!r}")
    for key in ("gain", "full_scale"):
        if fields.get(key) is not None and not math.isfinite(float(fields[key])):
            raise EditError(f"a track's {key.replace('_', ' ')} must be a finite number")
    return _put_track(project, replace(project.track(track_id), **fields))


def move_track(project: Project, track_id: str, index: int) -> Project:
    """Move a track to a position in the track list."""
    track = project.track(track_id)
    rest = [t for t in project.tracks if t.id != track_id]
    rest.insert(max(0, min(index, len(rest))), track)
    return replace(project, tracks=tuple(rest))


def _put_track(project: Project, track: Track) -> Project:
    return replace(project, tracks=tuple(track if t.id == track.id else t for t in project.tracks))
