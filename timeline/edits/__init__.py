"""Edits: pure functions from one project state to the next, each refusing bad input with nothing
changed (the undo history keeps the states).

One module per thing an edit changes: tracks (and a new project), palette (tiles and tabs),
clips, variants (their names are re-exported here: `edits.add_clip(...)`), tile_shape and
tile_params (a tile's points and parameters), placement (where a clip fits), markers, vibration
(vibrotactile designs and their emphasis), sound_track (the source sound), naming (unique
names for new tiles); history is undo/redo.
"""

from timeline.edits.clips import (
    add_clip,
    add_clips,
    duplicate_clip,
    invert_clip,
    merge_clips,
    move_clip,
    remove_clip,
    remove_clips,
    reverse_clip,
    scale_clip,
    set_clip,
    set_clip_gain,
    set_fade,
    set_pivot,
    shift_clips,
    split_clip,
    stretch_clip,
    trim_clip,
)
from timeline.edits.palette import (
    add_tab,
    add_tile,
    place_tile,
    remove_tab,
    remove_tile,
    rename_tab,
    rename_tile,
    replace_tile,
)
from timeline.edits.tracks import (
    add_track,
    move_track,
    new_project,
    remove_track,
    set_track,
)
from timeline.edits.variants import (
    remove_variant,
    save_variant,
    switch_variant,
)
from timeline.errors import EditError

__all__ = [
    "EditError",
    "add_clip",
    "add_clips",
    "add_tab",
    "add_tile",
    "add_track",
    "duplicate_clip",
    "invert_clip",
    "merge_clips",
    "move_clip",
    "move_track",
    "new_project",
    "place_tile",
    "remove_clip",
    "remove_clips",
    "remove_tab",
    "remove_tile",
    "remove_track",
    "remove_variant",
    "rename_tab",
    "rename_tile",
    "replace_tile",
    "reverse_clip",
    "save_variant",
    "scale_clip",
    "set_clip",
    "set_clip_gain",
    "set_fade",
    "set_pivot",
    "set_track",
    "shift_clips",
    "split_clip",
    "stretch_clip",
    "switch_variant",
    "trim_clip",
]
