"""Icons to compare taken from one project: its saved variants, or the tiles of a palette tab."""

from __future__ import annotations

from dataclasses import replace

from timeline import edits
from timeline.errors import HapticTimelineError
from timeline.limits.design import variant_project
from timeline.model import Project

LAYER_FOR_TILES = {"time": "drive", "position": "torque"}


def variant_icons(project: Project) -> list[tuple[str, Project]]:
    """A project's saved variants as icons."""
    return [(v.name, variant_project(project, v.name)) for v in project.variants]


def tab_icons(project: Project, tab: str) -> list[tuple[str, Project]]:
    """Each tile of a palette tab alone on a drive (time) or torque (position) track, at gain 1.

    A tile has no meaning until a layer gives it one; these are the layers a palette's
    vibrations and detents are designed for.
    """
    icons = []
    for tile_id in project.tab(tab).tile_ids:
        tile = project.tile(tile_id)
        p = edits.new_project(project.axis)
        p = replace(p, rate=project.rate)
        p, track = edits.add_track(p, LAYER_FOR_TILES[project.axis])
        p, new_id = edits.add_tile(p, tile)
        p, _ = edits.add_clip(p, track, new_id, 0.0)
        name = tile.name or tile_id
        taken = sum(1 for other, _ in icons if other == name or other.startswith(f"{name} ("))
        icons.append((f"{name} ({taken + 1})" if taken else name, p))
    if len(icons) < 2:
        raise HapticTimelineError(f"the {tab!r} tab needs two tiles to compare")
    return icons
