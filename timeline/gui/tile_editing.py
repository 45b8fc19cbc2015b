"""One way to edit a tile from the editor: as one undo step, and never a template in place."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from timeline.edits import tile_params

from .document import Document

COPY_NOTE = "a template is never changed: you are editing a copy in Scratch"


def edit_tile(
    doc: Document,
    label: str,
    tile_id: str,
    edit: Callable[..., Any],
    *args: Any,
    merge_key: object = None,
) -> Any:
    """Apply edit(project, tile_id, *args) to a tile (a template is copied to Scratch first and
    the selected clips play the copy); returns the edit's extra result, None if refused."""
    clips = list(doc.selected_clips)

    def on_editable(project):
        project, target = tile_params.editable(project, tile_id, clips)
        result = edit(project, target, *args)
        project, extra = result if isinstance(result, tuple) else (result, True)
        return project, (target, extra)

    done = doc.apply(label, on_editable, merge_key=merge_key)
    if done is None:
        return None
    target, extra = done
    if target != tile_id:
        doc.select_tile(target)
        doc.message.emit(COPY_NOTE, "info")
    return extra
