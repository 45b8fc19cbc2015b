"""Variants: named A/B snapshots of a design, saved, switched to and removed."""

from __future__ import annotations

from dataclasses import replace

from timeline.errors import EditError
from timeline.model import (
    Project,
    Variant,
)


def save_variant(project: Project, name: str) -> Project:
    """Snapshot the current design as a named variant (replacing one of that name)."""
    if not name.strip():
        raise EditError("a variant needs a name")
    snap = Variant(name, project.tracks, project.tiles)
    others = tuple(v for v in project.variants if v.name != name)
    return replace(project, variants=others + (snap,), active_variant=name)


def switch_variant(project: Project, name: str) -> Project:
    """Switch the design to a variant, first keeping the current design in the active one.

    The variant's tracks come back with its tile shapes; tiles added since stay in the library
    (the palette may list them), so nothing the user made disappears.
    """
    target = project.variant(name)
    if project.active_variant and project.active_variant != name:
        project = save_variant(project, project.active_variant)
        target = project.variant(name)
    tiles = project.tiles.update(target.tiles)
    return replace(project, tracks=target.tracks, tiles=tiles, active_variant=name)


def remove_variant(project: Project, name: str) -> Project:
    """Forget a variant."""
    project.variant(name)
    active = None if project.active_variant == name else project.active_variant
    return replace(
        project,
        variants=tuple(v for v in project.variants if v.name != name),
        active_variant=active,
    )
