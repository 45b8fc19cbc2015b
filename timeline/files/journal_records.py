"""What one edit changed, as JSON: the record an autosave journal appends (timeline.files.journal).

Projects are immutable and an edit shares every part it did not change, so the change from one
state to the next is found by identity: a track, tile, palette tab or variant that is the same
object is named, not written. A changed track is written without its clips but with the run of
clips between the longest shared head and tail (a clip still the same object named by its id),
so moving one clip of a 20,000-clip track writes a few clips. Tracks, clips and tiles use the
project file's own JSON (timeline.files.projectfile); a recording is not in the record but named
by its content key, its samples written once to the journal beside it (`new_media`).
"""

from __future__ import annotations

import dataclasses
import operator
from collections.abc import Iterable, Mapping, Sequence
from typing import Any

import numpy as np
from immutables import Map

from timeline.errors import FieldError
from timeline.files import project_fields as fields
from timeline.files import projectfile as pf
from timeline.model import Clip, PaletteTab, Project, Track, Variant, map_changes
from timeline.model.id_sequence import IdSequence
from timeline.tiles import SampledTile, Tile

Media = dict[str, SampledTile]  # content key -> a tile holding those samples
Pool = Mapping[str, np.ndarray]  # content key -> samples, for reading records back


def _same_run(old: Iterable, new: Iterable) -> int:
    """How many leading items of the two are the same objects."""
    same = list(map(operator.is_, old, new))
    return same.index(False) if False in same else len(same)


def _clips_delta(old: Track | None, new: Track) -> dict[str, Any]:
    before = old.clips if old is not None else ()
    after = new.clips
    head = _same_run(before, after)
    tail = _same_run(reversed(before[head:]), reversed(after[head:]))
    middle = after[head : len(after) - tail]
    known = old.clips_by_id if old is not None and middle else {}
    mid = [c.id if known.get(c.id) is c else pf.clip_to_json(c) for c in middle]
    return {"head": head, "tail": tail, "mid": mid}


def _track_delta(old: Track | None, new: Track) -> dict[str, Any]:
    doc = pf.track_to_json(new, lambda _: [])
    doc["clips"] = _clips_delta(old, new)
    return doc


def _tile_json(tile: Tile, media: Media) -> dict[str, Any]:
    """The tile as the project file writes it; a recording is named by its key, kept in media."""
    if isinstance(tile, SampledTile):
        media[tile.key] = tile
    return pf.tile_to_json(tile, {}, lambda _: {})


def _tiles_delta(old: Map, new: Map, media: Media) -> dict[str, Any]:
    changed, gone = map_changes(old, new)
    return {"set": {k: _tile_json(t, media) for k, t in changed.items()}, "del": list(gone)}


def _variant_json(variant: Variant, media: Media) -> dict[str, Any]:
    return {
        "name": variant.name,
        "tiles": {k: _tile_json(t, media) for k, t in variant.tiles.items()},
        "tracks": [pf.track_to_json(t) for t in variant.tracks],
    }


def delta(old: Project, new: Project) -> tuple[dict[str, Any], Media]:
    """The change from `old` to `new` as a JSON-ready dict, and the recordings it names."""
    media: Media = {}
    doc: dict[str, Any] = {}
    for name in ("axis", "rate", "next_id", "active_variant"):
        if getattr(old, name) != getattr(new, name):
            doc[name] = getattr(new, name)
    if old.metadata is not new.metadata and dict(old.metadata) != dict(new.metadata):
        doc["metadata"] = dict(new.metadata)
    if (old.markers, old.loop) != (new.markers, new.loop):
        doc["markers"] = pf.markers_json(new)
    if old.tracks is not new.tracks:
        by_id = {t.id: t for t in old.tracks}
        doc["tracks"] = [
            t.id if by_id.get(t.id) is t else _track_delta(by_id.get(t.id), t) for t in new.tracks
        ]
    if old.tiles is not new.tiles:
        doc["tiles"] = _tiles_delta(old.tiles, new.tiles, media)
    if old.palette is not new.palette:
        tabs = {id(t): i for i, t in enumerate(old.palette)}
        doc["palette"] = [
            tabs[id(t)]
            if id(t) in tabs
            else {"name": t.name, "role": t.role, "tiles": list(t.tile_ids)}
            for t in new.palette
        ]
    if old.variants is not new.variants:
        kept = {id(v): i for i, v in enumerate(old.variants)}
        doc["variants"] = [
            kept[id(v)] if id(v) in kept else _variant_json(v, media) for v in new.variants
        ]
    return doc, media


def media_keys(project: Project) -> set[str]:
    """The content keys of every recording the project and its variants hold."""
    tiles = [*project.tiles.values(), *(t for v in project.variants for t in v.tiles.values())]
    return {t.key for t in tiles if isinstance(t, SampledTile)}


def media_pool(project: Project) -> dict[str, np.ndarray]:
    """Content key -> samples of every recording in the project and its variants."""
    tiles = [*project.tiles.values(), *(t for v in project.variants for t in v.tiles.values())]
    return {t.key: t.data for t in tiles if isinstance(t, SampledTile)}


# --- reading -----------------------------------------------------------------------------------


def _tile(obj: Any, pool: Pool, where: str) -> Tile:
    if isinstance(obj, dict) and obj.get("type") == "sampled":
        key = fields.get(obj, "media", str, where)
        if key not in pool:
            raise FieldError(f"{where} names recording {key!r}, which the journal lacks")
        rate = fields.number(obj, "rate", where, positive=True)
        name, source = fields.get(obj, "name", str, where), fields.text(obj, "source", where, "")
        return SampledTile.from_checked(pool[key], rate, name, source, key)
    return pf.tile_from_json(obj, {}, where)


def _clips(old: Track | None, obj: Any, where: str) -> tuple[Clip, ...]:
    before = old.clips if old is not None else ()
    head = fields.integer(obj, "head", where, 0, len(before))
    tail = fields.integer(obj, "tail", where, 0, len(before) - head)
    by_id = old.clips_by_id if old is not None else {}
    mid = []
    for i, item in enumerate(fields.get(obj, "mid", list, where)):
        if isinstance(item, str):
            if item not in by_id:
                raise FieldError(f"{where} names clip {item!r}, which the track lacks")
            mid.append(by_id[item])
        else:
            mid.append(pf.clip_from_json(item, f"{where}.mid[{i}]"))
    return (*before[:head], *mid, *before[len(before) - tail :])


def _tracks(old: Sequence[Track], items: Any) -> tuple[Track, ...]:
    by_id = {t.id: t for t in old}
    tracks = []
    for i, item in enumerate(fields.get({"tracks": items}, "tracks", list, "record")):
        where = f"record.tracks[{i}]"
        if isinstance(item, str):
            if item not in by_id:
                raise FieldError(f"{where} names track {item!r}, which the project lacks")
            tracks.append(by_id[item])
            continue
        shell = pf.track_from_json({**fields.obj(item, where), "clips": []}, where)
        clips = _clips(by_id.get(shell.id), item.get("clips"), f"{where}.clips")
        tracks.append(dataclasses.replace(shell, clips=clips))
    return tuple(tracks)


def _tiles(old: Map, obj: Any, pool: Pool) -> Map:
    changed = fields.get(obj, "set", dict, "record.tiles")
    tiles = old.mutate()
    for key in fields.get(obj, "del", list, "record.tiles"):
        tiles.pop(key, None)
    for key, value in changed.items():
        tiles[key] = pf.built_at(lambda v=value, k=key: _tile(v, pool, f"tile {k!r}"), key)
    return tiles.finish()


def _palette(old: Sequence[PaletteTab], items: Any) -> tuple[PaletteTab, ...]:
    tabs = []
    for item in fields.get({"palette": items}, "palette", list, "record"):
        if isinstance(item, int):
            tabs.append(old[item])
        else:
            tiles = fields.get(item, "tiles", list, "palette tab")
            tabs.append(
                PaletteTab(
                    fields.get(item, "name", str, "palette tab"),
                    fields.get(item, "role", str, "palette tab"),
                    IdSequence(pf.checked_tile_ids(tiles)),
                )
            )
    return tuple(tabs)


def _variants(old: Sequence[Variant], items: Any, pool: Pool) -> tuple[Variant, ...]:
    variants = []
    for i, item in enumerate(fields.get({"variants": items}, "variants", list, "record")):
        if isinstance(item, int):
            variants.append(old[item])
            continue
        where = f"variant {i}"
        tiles = fields.get(item, "tiles", dict, where)
        tracks = fields.get(item, "tracks", list, where)
        variants.append(
            Variant(
                fields.get(item, "name", str, where),
                tuple(pf.track_from_json(t, f"{where}.tracks") for t in tracks),
                Map({k: _tile(v, pool, f"{where} tile {k!r}") for k, v in tiles.items()}),
            )
        )
    return tuple(variants)


def apply(old: Project, doc: Any, pool: Pool) -> Project:
    """The project `old` becomes with a record of delta(old, new): equal to `new`.

    FieldError (or EditError, IndexError) for a record that does not fit `old`.
    """
    doc = fields.obj(doc, "record")
    changes: dict[str, Any] = {k: doc[k] for k in ("axis", "rate", "next_id") if k in doc}
    if "active_variant" in doc:
        changes["active_variant"] = doc["active_variant"]
    if "metadata" in doc:
        changes["metadata"] = fields.get(doc, "metadata", dict, "record")
    if "markers" in doc:
        changes["markers"], changes["loop"] = pf.markers_from_json(doc["markers"])
    if "tracks" in doc:
        changes["tracks"] = _tracks(old.tracks, doc["tracks"])
    if "tiles" in doc:
        changes["tiles"] = _tiles(old.tiles, doc["tiles"], pool)
    if "palette" in doc:
        changes["palette"] = _palette(old.palette, doc["palette"])
    if "variants" in doc:
        changes["variants"] = _variants(old.variants, doc["variants"], pool)
    return dataclasses.replace(old, **changes) if changes else old
