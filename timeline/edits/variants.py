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


def removed_names(before: Project, after: Project) -> frozenset[str]:
    """The variants an edit removed (a deletion step's, or a new project's)."""
    return frozenset(v.name for v in before.variants) - {v.name for v in after.variants}


def kept_across(
    shown: Project, target: Project, removed: frozenset[str], restored: dict[str, Variant]
) -> Project:
    """`target` (a step undo, redo or a history jump arrives at) with every variant still alive.

    A variant outlives the steps it was saved in: only its own deletion removes it. `removed`
    names the variants deleted by the steps redone on the way; `restored` holds the ones whose
    deletion was undone on the way. A variant the target has comes back as it was at that step.
    """
    kept = {v.name: v for v in shown.variants if v.name not in removed}
    for name, variant in restored.items():
        kept.setdefault(name, variant)
    ordered = list(target.variants)
    names = {v.name for v in ordered}
    ordered += [v for name, v in kept.items() if name not in names]
    if len(ordered) == len(target.variants):
        return target
    return replace(target, variants=tuple(ordered))
