"""Variants for A/B comparison by feel: save under the next free letter, cycle with one key."""

from __future__ import annotations

import string

from timeline import edits
from timeline.errors import EditError
from timeline.model import Project


def next_name(project: Project) -> str:
    """The first of A, B, C, ... not yet used by a variant."""
    used = {v.name for v in project.variants}
    return next(c for c in string.ascii_uppercase + "".join(map(str, range(10))) if c not in used)


def save_next(project: Project, name: str = "") -> Project:
    """Save the current design as a variant (named, or the next free letter)."""
    return edits.save_variant(project, name.strip() or next_name(project))


def switch_next(project: Project) -> Project:
    """Switch to the variant after the active one (wrapping around)."""
    names = [v.name for v in project.variants]
    if not names:
        raise EditError("there are no variants yet: save one first (Ctrl+Shift+V)")
    i = names.index(project.active_variant) if project.active_variant in names else -1
    return edits.switch_variant(project, names[(i + 1) % len(names)])
