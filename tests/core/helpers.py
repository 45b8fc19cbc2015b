"""Small builders shared by the core tests."""

from __future__ import annotations

from timeline import edits
from timeline.model import Project
from timeline.tiles import Tile


def one_clip(tile: Tile, kind: str = "drive", start: float = 0.0, **fields) -> tuple[Project, str]:
    """A time project (no templates) with one track holding one clip of the tile."""
    p = edits.new_project(templates=False)
    p, track = edits.add_track(p, kind)
    p, tile_id = edits.add_tile(p, tile)
    p, clip = edits.add_clip(p, track, tile_id, start, **fields)
    return p, clip
