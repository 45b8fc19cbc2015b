"""Clips on the clipboard: a small project (the .htl format) holding copies of the chosen clips,
their tiles and their tracks' kinds, that pastes into any project of the same axis. Qt-free.

The snippet is ordinary project JSON, so a programmer can paste it into a script and load it
with `timeline.files.projectfile.loads`, and the editor validates it like any file it opens.
"""

from __future__ import annotations

from dataclasses import fields, replace
from types import MappingProxyType

from immutables import Map

from timeline import edits
from timeline.errors import EditError
from timeline.files import projectfile
from timeline.model import Clip, Project, Track

MIME = "application/x-haptic-timeline-clips"
_COPIED_FIELDS = tuple(f.name for f in fields(Clip) if f.name not in ("id", "tile_id", "start"))


def snippet(project: Project, clip_ids: list[str]) -> Project:
    """The chosen clips (moved so the earliest starts at 0) with their tiles and tracks' kinds."""
    if not clip_ids:
        raise EditError("select clips to copy")
    chosen = set(clip_ids)
    for clip_id in chosen:
        project.find_clip(clip_id)
    t0 = min(project.find_clip(i)[1].start for i in chosen)
    tracks = tuple(
        Track(
            t.id,
            t.kind,
            t.name,
            tuple(replace(c, start=c.start - t0) for c in t.clips if c.id in chosen),
        )
        for t in project.tracks
        if any(c.id in chosen for c in t.clips)
    )
    tiles = {c.tile_id: project.tiles[c.tile_id] for t in tracks for c in t.clips}
    return Project(
        axis=project.axis,
        rate=project.rate,
        tracks=tracks,
        tiles=Map(tiles),
        metadata=MappingProxyType({"title": "clipboard"}),
        next_id=project.next_id,
    )


def to_text(clips: Project) -> str:
    """The snippet as project-file JSON text."""
    return projectfile.dumps(clips)


def from_text(text: str | bytes) -> Project:
    """Read a snippet (or any project file's text); one ProjectFileError sentence if it is not."""
    return projectfile.loads(text, "the clipboard")


def paste(
    project: Project, clips: Project, at: float, track_id: str | None = None
) -> tuple[Project, list[str]]:
    """Put a snippet's clips into a project with the earliest at `at`; returns the new clip ids.

    The snippet's first track lands on `track_id` (by default the first track of its kind), the
    next ones on the lanes below; where there is no lane, a track of the snippet's kind is added.
    A tile equal to one the project has is reused; others go to the Scratch tab.
    """
    if clips.axis != project.axis:
        raise EditError(f"clips from a {clips.axis} project cannot go into a {project.axis} one")
    if not any(t.clips for t in clips.tracks):
        raise EditError("the clipboard holds no clips")
    order = [t.id for t in project.tracks]
    if track_id is None:
        first = clips.tracks[0].kind
        track_id = next((t.id for t in project.tracks if t.kind == first), None)
    base = order.index(track_id) if track_id in order else len(order)
    tile_ids: dict[str, str] = {}
    new_ids: list[str] = []
    offset = max(0.0, at)
    for i, source in enumerate(clips.tracks):
        if base + i < len(order):
            target = order[base + i]
        else:
            project, target = edits.add_track(project, source.kind, source.name)
        for clip in source.clips:
            if clip.tile_id not in tile_ids:
                tile_ids[clip.tile_id] = _tile_for(project, clips, clip.tile_id)
                if tile_ids[clip.tile_id] not in project.tiles:
                    project, tile_ids[clip.tile_id] = edits.add_tile(
                        project, clips.tiles[clip.tile_id], "Scratch"
                    )
            extra = {name: getattr(clip, name) for name in _COPIED_FIELDS}
            project, new_id = edits.add_clip(
                project, target, tile_ids[clip.tile_id], offset + clip.start, **extra
            )
            new_ids.append(new_id)
    return project, new_ids


def _tile_for(project: Project, clips: Project, tile_id: str) -> str:
    """The id of a tile in the project equal to the snippet's tile, or "" when there is none."""
    tile = clips.tiles[tile_id]
    if project.tiles.get(tile_id) == tile:
        return tile_id
    return next((k for k, v in project.tiles.items() if v == tile), "")
