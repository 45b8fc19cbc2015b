"""Clip edits: add, remove, move, shift, duplicate, trim, split, stretch, gain, scale and invert
about a pivot line, reverse, fades, and merge (superimposition into one new tile).

Pure functions like every edit: bad input raises EditError and nothing has changed; functions
that create something return (project, new_id). Overlapping clips on one track add.

    split_clip at t:   [====A====]      ->  [==A==][==B==]   (joined, renders the same)
    trim_clip:         [====A====]      ->    [==A==]        (content stays where it was)
    stretch_clip x2:   [==A==]          ->  [====A====]      (squeeze: half the frequency)
"""

from __future__ import annotations

import math
from bisect import bisect_left, bisect_right
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import replace
from typing import Any

import numpy as np

from timeline.edits.naming import unique_tile_name
from timeline.edits.palette import add_tile
from timeline.errors import EditError
from timeline.model import (
    Clip,
    Fade,
    Project,
    Track,
)
from timeline.plugins.track_kinds import track_kind
from timeline.rendering.clip_render import clip_samples, render_shape
from timeline.signal.render_presets import preset
from timeline.tiles import SampledTile, Tile

_EDGE_TOLERANCE = 1e-9  # relative slack when a source edge lands on the tile's end


def _check_source(project: Project, clip: Clip) -> Clip:
    tile = project.tile(clip.tile_id)
    slack = _EDGE_TOLERANCE * max(1.0, tile.duration)
    if clip.source_in < -slack or clip.source_out > tile.duration + slack:
        raise EditError(
            f"the clip would play {clip.source_in:.6g} to {clip.source_out:.6g} of a tile that "
            f"lasts {tile.duration:.6g} {project.unit}"
        )
    for fade in (clip.fade_in, clip.fade_out):
        if fade.length > clip.duration * (1 + _EDGE_TOLERANCE):
            raise EditError(
                f"a fade of {fade.length:.6g} is longer than the clip ({clip.duration:.6g})"
            )
    return clip


def _put_clip(
    project: Project, clip: Clip, track_id: str | None = None, new: bool = False
) -> Project:
    """Replace a clip (same id) or add it to a track.

    Only the tracks that lose or gain the clip are rebuilt (the others are shared with the
    previous state), and the clip goes in by bisection on (start, id), so an edit costs a tuple
    copy of one track rather than a walk over every clip.
    """
    _check_source(project, clip)
    source = None if new else next((t for t in project.tracks if clip.id in t.clips_by_id), None)
    target = track_id or (source.id if source is not None else None)
    if target is None:
        raise EditError(f"there is no clip {clip.id!r}")
    changed: dict[str, Track] = {}
    if source is not None:
        old = source.clips_by_id[clip.id]
        at = bisect_left(source.clips, _order(old), key=_order)
        if at < len(source.clips) and source.clips[at] is old:  # in order, as edits keep it
            kept = source.clips[:at] + source.clips[at + 1 :]
        else:
            kept = tuple(c for c in source.clips if c.id != clip.id)
        changed[source.id] = source.with_clips(kept, gone=[old])
    track = changed.get(target) or project.track(target)
    at = bisect_right(track.clips, (clip.start, clip.id), key=_order)
    changed[target] = track.with_clips(track.clips[:at] + (clip,) + track.clips[at:], came=[clip])
    return replace(project, tracks=tuple(changed.get(t.id, t) for t in project.tracks))


def _order(clip: Clip) -> tuple[float, str]:
    """The order of clips on a track: by start, then id."""
    return (clip.start, clip.id)


def add_clip(
    project: Project, track_id: str, tile_id: str, start: float, **fields: Any
) -> tuple[Project, str]:
    """Place a tile on a track at a start (seconds, or radians on the position axis)."""
    project.track(track_id)
    tile = project.tile(tile_id)
    fields.setdefault("source_in", 0.0)
    fields.setdefault("source_out", tile.duration)
    project, clip_id = project.with_id("c")
    clip = Clip(id=clip_id, tile_id=tile_id, start=start, **fields)
    return _put_clip(project, clip, track_id, new=True), clip_id


def add_clips(
    project: Project,
    items: Sequence[tuple[str, Tile | str, float, Mapping[str, Any]]],
    tab: str = "Scratch",
) -> tuple[Project, list[str]]:
    """Many add_tile/add_clip steps in one pass: the same project and ids, in O(n log n).

    Each item is (track id, a tile id or a new tile, start, clip fields); a new tile goes to the
    library and `tab` before its clip (one tile object given twice is added once).
    """
    project.tab(tab)
    ids = project.next_id
    tiles = project.tiles.mutate()
    new_tiles: dict[int, str] = {}
    order: list[str] = []
    pending: list[tuple[str, str, str, float, Mapping[str, Any]]] = []
    for track_id, tile, start, fields in items:
        project.track(track_id)
        if isinstance(tile, str):
            project.tile(tile)
            tile_id = tile
        elif id(tile) in new_tiles:
            tile_id = new_tiles[id(tile)]
        else:
            tile_id = new_tiles[id(tile)] = f"tile{ids}"  # as Project.with_id names them
            tiles[tile_id] = tile
            order.append(tile_id)
            ids += 1
        pending.append((track_id, tile_id, f"c{ids}", start, fields))
        ids += 1
    palette = tuple(
        replace(t, tile_ids=t.tile_ids + order) if t.name == tab else t for t in project.palette
    )
    project = replace(project, tiles=tiles.finish(), palette=palette)
    added: dict[str, list[Clip]] = {}
    for track_id, tile_id, clip_id, start, fields in pending:
        given = {"source_in": 0.0, "source_out": project.tile(tile_id).duration, **fields}
        clip = _check_source(project, Clip(id=clip_id, tile_id=tile_id, start=start, **given))
        added.setdefault(track_id, []).append(clip)
    tracks = tuple(
        replace(t, clips=tuple(sorted(t.clips + tuple(added[t.id]), key=_order)))
        if t.id in added
        else t
        for t in project.tracks
    )
    return replace(project, tracks=tracks, next_id=ids), [p[2] for p in pending]


def remove_clips(project: Project, clip_ids: Iterable[str]) -> Project:
    """Remove clips."""
    ids = set(clip_ids)
    for clip_id in ids:
        project.find_clip(clip_id)
    tracks = tuple(
        t.with_clips(tuple(c for c in t.clips if c.id not in ids), [t.clips_by_id[i] for i in gone])
        if (gone := ids.intersection(t.clips_by_id))
        else t
        for t in project.tracks
    )
    return replace(project, tracks=tracks)


def remove_clip(project: Project, clip_id: str) -> Project:
    """Remove one clip."""
    return remove_clips(project, [clip_id])


def set_clip(project: Project, clip_id: str, **fields: Any) -> Project:
    """Change any clip fields directly (the numeric boxes of the editor)."""
    if "id" in fields or "tile_id" in fields:
        raise EditError("a clip's id and tile cannot be changed this way")
    _, clip = project.find_clip(clip_id)
    return _put_clip(project, replace(clip, **fields))


def move_clip(
    project: Project, clip_id: str, start: float | None = None, track_id: str | None = None
) -> Project:
    """Move a clip in time and/or to another track (its meaning comes from the new track)."""
    track, clip = project.find_clip(clip_id)
    target = project.track(track_id) if track_id else track
    moved = replace(clip, start=clip.start if start is None else start)
    return _put_clip(project, moved, target.id)


def shift_clips(project: Project, clip_ids: Iterable[str], shift: float) -> Project:
    """Move clips by one time shift on their tracks (as move_clip on each), each changed track
    rebuilt once: dragging a design with thousands of emphasis clips stays linear."""
    ids = set(clip_ids)
    for clip_id in ids:
        project.find_clip(clip_id)
    if not math.isfinite(shift):
        raise EditError(f"clips move by a finite time, not {shift!r}")
    if not ids:  # a drag carrying no other clip: every track stays the same object
        return project
    changed = {}
    for track in project.tracks:
        if not ids.isdisjoint(track.clips_by_id):
            gone = [c for c in track.clips if c.id in ids]
            came = {c.id: replace(c, start=c.start + shift) for c in gone}
            clips = tuple(sorted((came.get(c.id, c) for c in track.clips), key=_order))
            changed[track.id] = track.with_clips(clips, gone, came.values())
    return replace(project, tracks=tuple(changed.get(t.id, t) for t in project.tracks))


def duplicate_clip(
    project: Project, clip_id: str, start: float | None = None, track_id: str | None = None
) -> tuple[Project, str]:
    """Copy a clip; by default the copy starts where the original ends."""
    track, clip = project.find_clip(clip_id)
    project, new_id = project.with_id("c")
    copy = replace(clip, id=new_id, start=clip.end if start is None else start)
    return _put_clip(project, copy, track_id or track.id, new=True), new_id


def _trimmed(clip: Clip, new_start: float, new_end: float) -> Clip:
    """The clip cut to the timeline range [new_start, new_end), content staying in place."""
    if not new_end > new_start:
        raise EditError("a clip cannot be trimmed to nothing")
    a, z = new_start - clip.start, new_end - clip.start
    if clip.stretch_mode == "repeat":
        length = clip.source_length
        return replace(
            clip,
            start=new_start,
            stretch=(z - a) / length,
            loop_phase=math.fmod(math.fmod(clip.loop_phase + a, length) + length, length),
            fade_in=_fit(clip.fade_in, z - a),
            fade_out=_fit(clip.fade_out, z - a),
        )
    s = clip.stretch
    if clip.reverse:
        src_in, src_out = clip.source_out - z / s, clip.source_out - a / s
    else:
        src_in, src_out = clip.source_in + a / s, clip.source_in + z / s
    return replace(
        clip,
        start=new_start,
        source_in=src_in,
        source_out=src_out,
        fade_in=_fit(clip.fade_in, z - a),
        fade_out=_fit(clip.fade_out, z - a),
    )


def _fit(fade: Fade, duration: float) -> Fade:
    return fade if fade.length <= duration else replace(fade, length=duration)


def trim_clip(
    project: Project, clip_id: str, start: float | None = None, end: float | None = None
) -> Project:
    """Move a clip's left and/or right edge, keeping its content where it is."""
    _, clip = project.find_clip(clip_id)
    trimmed = _trimmed(
        clip, clip.start if start is None else start, clip.end if end is None else end
    )
    return _put_clip(project, trimmed)


def split_clip(project: Project, clip_id: str, at: float) -> tuple[Project, str]:
    """Split a clip at a time into two clips that together render as the original."""
    track, clip = project.find_clip(clip_id)
    if not clip.start < at < clip.end:
        raise EditError(f"{at:.6g} is not inside the clip ({clip.start:.6g} to {clip.end:.6g})")
    left = replace(_trimmed(clip, clip.start, at), fade_out=Fade(), fade_in=clip.fade_in)
    right = replace(_trimmed(clip, at, clip.end), fade_in=Fade(), fade_out=clip.fade_out)
    project, right_id = project.with_id("c")
    left = replace(left, fade_in=_fit(clip.fade_in, left.duration))
    right = replace(right, id=right_id, fade_out=_fit(clip.fade_out, right.duration))
    project = _put_clip(project, left)
    return _put_clip(project, right, track.id, new=True), right_id


def stretch_clip(project: Project, clip_id: str, factor: float, mode: str | None = None) -> Project:
    """Make a clip `factor` times longer: squeeze resamples it, repeat loops it (start stays)."""
    if not (math.isfinite(factor) and factor > 0):
        raise EditError(f"a stretch factor must be a positive number, not {factor}")
    _, clip = project.find_clip(clip_id)
    stretched = replace(clip, stretch=clip.stretch * factor, stretch_mode=mode or clip.stretch_mode)
    duration = stretched.duration
    stretched = replace(
        stretched, fade_in=_fit(clip.fade_in, duration), fade_out=_fit(clip.fade_out, duration)
    )
    return _put_clip(project, stretched)


def set_clip_gain(project: Project, clip_id: str, gain: float) -> Project:
    """Set a clip's overall gain."""
    return set_clip(project, clip_id, gain=gain)


def scale_clip(
    project: Project, clip_id: str, factor: float, pivot: float | None = None
) -> Project:
    """Scale a clip's amplitude by factor about a horizontal mirror line (the paper's drag)."""
    _, clip = project.find_clip(clip_id)
    p = clip.pivot if pivot is None else float(pivot)
    # y -> p + f*(y - p) applied to y = scale*shape + offset
    return set_clip(
        project,
        clip_id,
        scale=clip.scale * factor,
        offset=p + factor * (clip.offset - p),
        pivot=p,
    )


def invert_clip(project: Project, clip_id: str, pivot: float | None = None) -> Project:
    """Mirror a clip about a horizontal line (its pivot line by default)."""
    return scale_clip(project, clip_id, -1.0, pivot)


def set_pivot(project: Project, clip_id: str, pivot: float) -> Project:
    """Place a clip's horizontal mirror line (does not change its sound)."""
    return set_clip(project, clip_id, pivot=pivot)


def reverse_clip(project: Project, clip_id: str) -> Project:
    """Play a clip backwards."""
    _, clip = project.find_clip(clip_id)
    return set_clip(project, clip_id, reverse=not clip.reverse)


def set_fade(
    project: Project, clip_id: str, which: str, length: float, shape: str = "linear"
) -> Project:
    """Set a clip's fade "in" or "out" to a length and shape (0 removes it)."""
    if which not in ("in", "out"):
        raise EditError(f"a fade is 'in' or 'out', not {which!r}")
    return set_clip(project, clip_id, **{f"fade_{which}": Fade(length, shape)})


def merge_clips(
    project: Project, clip_ids: Iterable[str], replace_clips: bool = True, name: str = "merged"
) -> tuple[Project, str]:
    """Superimpose clips of one kind into a new sampled tile in the Scratch tab.

    With replace_clips, the clips are removed and one clip of the new tile takes their place on
    the track of the earliest clip, so the design renders the same.
    """
    ids = list(dict.fromkeys(clip_ids))
    if not ids:
        raise EditError("select at least one clip to merge")
    found = [project.find_clip(i) for i in ids]
    kinds = {t.kind for t, _ in found}
    if len(kinds) > 1:
        raise EditError(f"only clips of one kind can be merged, not {', '.join(sorted(kinds))}")
    target, _ = min(found, key=lambda tc: (tc[1].start, tc[1].id))
    scale_of = {t.id: _track_scale(t) for t, _ in found}
    if scale_of[target.id] == 0:
        raise EditError(f"track {target.name!r} has zero gain, so a merge onto it cannot be heard")
    rate = project.rate
    t0 = min(c.start for _, c in found)
    # the mixer's placement on the grid t0 + i/rate: exact at any time and rate (every start is
    # at or after t0, so no clip starts before sample 0)
    spans = [(track, clip, clip_samples(clip, t0, rate)) for track, clip in found]
    total = np.zeros(max(1, max(i1 for _, _, (_, i1, _) in spans)))
    exact = preset("exact")
    for track, clip, (i0, i1, phase) in spans:
        if i1 > i0:
            tile = project.tile(clip.tile_id)
            values = render_shape(clip, tile, phase, rate, i1 - i0, exact, clip.gain)
            total[i0:i1] += values * (scale_of[track.id] / scale_of[target.id])
    name = unique_tile_name(project, name)  # "merged", "merged 2", ...
    tile = SampledTile(total, rate, name, source="merge of " + ", ".join(ids))
    project, tile_id = add_tile(project, tile, "Scratch")
    if replace_clips:
        project = remove_clips(project, ids)
        project, _ = add_clip(project, target.id, tile_id, t0)
    return project, tile_id


def _track_scale(track: Track) -> float:
    return track.gain * (
        track_kind(track.kind).full_scale if track.full_scale is None else track.full_scale
    )
