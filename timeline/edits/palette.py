"""Edits of the tile palette: tiles added, replaced, removed, renamed; tabs; a tile placed on a tab.

Pure functions like every edit: bad input raises EditError and nothing has changed.
"""

from __future__ import annotations

from dataclasses import replace

from timeline.errors import EditError
from timeline.model import (
    PaletteTab,
    Project,
)
from timeline.tiles import Tile


def add_tile(project: Project, tile: Tile, tab: str = "Scratch") -> tuple[Project, str]:
    """Add a tile to the library and to a palette tab."""
    project.tab(tab)
    project, tile_id = project.with_id("tile")
    palette = tuple(
        replace(t, tile_ids=t.tile_ids + (tile_id,)) if t.name == tab else t
        for t in project.palette
    )
    return replace(project, tiles=project.tiles.set(tile_id, tile), palette=palette), tile_id


def replace_tile(project: Project, tile_id: str, tile: Tile) -> Project:
    """Put a new shape under a tile id; refused if a clip would play past the new end."""
    project.tile(tile_id)
    for track in project.tracks:
        for clip in track.clips:
            if clip.tile_id == tile_id and clip.source_out > tile.duration * (1 + 1e-9):
                raise EditError(
                    f"a clip plays this tile up to {clip.source_out:.4g}; it cannot end at "
                    f"{tile.duration:.4g}"
                )
    return replace(project, tiles=project.tiles.set(tile_id, tile))


def remove_tile(project: Project, tile_id: str) -> Project:
    """Remove a tile that no clip uses."""
    project.tile(tile_id)
    users = [c.id for t in project.tracks for c in t.clips if c.tile_id == tile_id]
    if users:
        raise EditError(f"tile {tile_id!r} is used by {len(users)} clip(s); remove them first")
    palette = tuple(
        replace(t, tile_ids=tuple(i for i in t.tile_ids if i != tile_id)) for t in project.palette
    )
    return replace(project, tiles=project.tiles.delete(tile_id), palette=palette)


def rename_tile(project: Project, tile_id: str, name: str) -> Project:
    """Give a tile a new name."""
    tile = project.tile(tile_id).with_name(name)
    return replace(project, tiles=project.tiles.set(tile_id, tile))


def add_tab(project: Project, name: str) -> Project:
    """Add a user tab to the palette."""
    if any(t.name == name for t in project.palette):
        raise EditError(f"the palette already has a tab {name!r}")
    if not name.strip():
        raise EditError("a palette tab needs a name")
    return replace(project, palette=project.palette + (PaletteTab(name, "user"),))


def rename_tab(project: Project, name: str, new_name: str) -> Project:
    """Rename a user tab."""
    tab = project.tab(name)
    if tab.role != "user":
        raise EditError(f"the {name} tab cannot be renamed")
    if any(t.name == new_name for t in project.palette) or not new_name.strip():
        raise EditError(f"a palette tab cannot be called {new_name!r}")
    return replace(
        project,
        palette=tuple(replace(t, name=new_name) if t is tab else t for t in project.palette),
    )


def remove_tab(project: Project, name: str) -> Project:
    """Remove a user tab; its tiles stay in the library."""
    tab = project.tab(name)
    if tab.role != "user":
        raise EditError(f"the {name} tab cannot be removed")
    return replace(project, palette=tuple(t for t in project.palette if t is not tab))


def place_tile(project: Project, tile_id: str, tab: str) -> Project:
    """Show a library tile in a palette tab as well."""
    project.tile(tile_id)
    target = project.tab(tab)
    if tile_id in target.tile_ids:
        return project
    return replace(
        project,
        palette=tuple(
            replace(t, tile_ids=t.tile_ids + (tile_id,)) if t is target else t
            for t in project.palette
        ),
    )
