"""The .htl project file: JSON with a schema version, then sampled media as a binary appendix.

A saved file is human-readable JSON (the whole project), and when it holds recordings a marked
binary appendix of their raw samples, which the JSON's media entries name by offset, length and
hash (timeline.files.media; the layout is in docs/formats.md). The text form (dumps, loads: the
clipboard) keeps samples inside the JSON as base64, as files of schema 3 and older did; both
open. Loading runs no code (plain JSON, no pickle or eval), bounds every declared size, and turns
any malformed content, a truncated or damaged appendix among it, into one ProjectFileError
sentence. Saving is atomic: a crash mid-save leaves the previous file intact.
"""

from __future__ import annotations

import dataclasses
import io
import json
import math
import os
import typing
from collections.abc import Callable, Iterable, Iterator, Sequence
from operator import attrgetter, itemgetter
from pathlib import Path
from types import MappingProxyType
from typing import Any, NamedTuple

import numpy as np
from immutables import Map

from timeline.errors import EditError, FieldError, HapticTimelineError, NotPlain, ProjectFileError
from timeline.files import gc_pause
from timeline.files import media as sample_media
from timeline.files import project_fields as fields
from timeline.files.atomic import write_atomically
from timeline.model import Clip, Fade, PaletteTab, Project, Track, Variant
from timeline.model.id_sequence import IdSequence
from timeline.model.markers import LoopRegion, Marker
from timeline.signal.samples import ContentKey
from timeline.tiles import GeneratorTile, SampledTile, SplineTile, Tile
from timeline.tiles.vibration_tile import VibrationTile

FORMAT = "haptic-timeline"
SCHEMA = 5  # 2: vibration tiles; 3: markers and the loop region; 4: the binary appendix;
# 5: damping and mass full scales raised to what the device renders
MAX_FILE_BYTES = 4 * 2**30


def _schema_1_to_2(doc: dict) -> dict:
    """Schema 2 added the "vibration" tile type; a schema 1 file has none, so nothing changes."""
    return {**doc, "schema": 2}


def _schema_2_to_3(doc: dict) -> dict:
    """Schema 3 added markers and the loop region: an older project has none."""
    body = doc.get("project")
    if isinstance(body, dict):
        body = {**body, "markers": [], "loop": None}
    return {**doc, "schema": 3, "project": body}


def _schema_3_to_4(doc: dict) -> dict:
    """Schema 4 stores media raw in a binary appendix; base64 media entries stay valid."""
    return {**doc, "schema": 4}


# The damping and mass kinds' full scales up to schema 4 (N*m*s/rad, kg*m^2), for old files.
_SCHEMA_4_FULL_SCALES = {"damping": 1e-4, "mass": 1e-5}


def _pinned_tracks(tracks: Any) -> Any:
    """A list of track dicts with an absent or null full scale of a damping or mass track set to
    that kind's schema-4 full scale; anything malformed is left for the reader to report."""
    if not isinstance(tracks, list):
        return tracks
    pinned = []
    for track in tracks:
        kind = track.get("kind") if isinstance(track, dict) else None
        if (
            isinstance(kind, str)
            and kind in _SCHEMA_4_FULL_SCALES
            and track.get("full_scale") is None
        ):
            track = {**track, "full_scale": _SCHEMA_4_FULL_SCALES[kind]}
        pinned.append(track)
    return pinned


def _schema_4_to_5(doc: dict) -> dict:
    """Schema 5 raised the damping and mass kinds' full scales (0.2 N*m*s/rad, 2.8e-5 kg*m^2):
    an older damping or mass track of the kind's full scale keeps its old one, in the project
    and in every variant, so it renders as it did."""
    body = doc.get("project")
    if not isinstance(body, dict):
        return {**doc, "schema": 5}
    body = {**body}
    if "tracks" in body:
        body["tracks"] = _pinned_tracks(body["tracks"])
    if isinstance(body.get("variants"), list):
        body["variants"] = [
            {**v, "tracks": _pinned_tracks(v["tracks"])}
            if isinstance(v, dict) and "tracks" in v
            else v
            for v in body["variants"]
        ]
    return {**doc, "schema": 5, "project": body}


# Upgrade functions keyed by the schema version they read; each returns the next version's dict.
MIGRATIONS: dict[int, Callable[[dict], dict]] = {
    1: _schema_1_to_2,
    2: _schema_2_to_3,
    3: _schema_3_to_4,
    4: _schema_4_to_5,
}


# --- the clip schema ---------------------------------------------------------------------------
# A clip is stored as an object of its Clip fields, in Clip's order, each under its own name but
# tile_id (stored as "tile"); an absent field takes Clip's default, a field without one is
# required. A fade is an object of its Fade fields ({"length": number, "shape": text}), both
# required. Writing (a dict, or the one-line template of the project's clips) and reading (the
# plain-clip fast path, the field-by-field checks) all derive from these two tables.


class FileField(NamedTuple):
    """One field of a clip or a fade in a project file."""

    key: str  # its key in the file
    attr: str  # the attribute it holds
    kind: type  # str, float, bool or Fade
    default: Any  # what an absent key reads as; dataclasses.MISSING: the key is required


_FILE_KEYS = {"tile_id": "tile"}  # attributes stored under another key


def _fields_of(record: type, required: bool) -> tuple[FileField, ...]:
    kinds = typing.get_type_hints(record)
    return tuple(
        FileField(
            _FILE_KEYS.get(f.name, f.name),
            f.name,
            kinds[f.name],
            dataclasses.MISSING if required else f.default,
        )
        for f in dataclasses.fields(record)
    )


CLIP_FIELDS = _fields_of(Clip, required=False)
FADE_FIELDS = _fields_of(Fade, required=True)
_FIELDS = {Clip: CLIP_FIELDS, Fade: FADE_FIELDS}

# Writing: a clip as a dict of JSON values (a variant's clips), or the project's clips as lines of
# one %-template, filled column by column (each column one C loop over the clips: a loop over the
# fields in Python per clip takes a quarter longer, which 100,000 clips feel).
_COMPACT = json.JSONEncoder(allow_nan=False, separators=(", ", ": "))
_LEAF_PIECE = {str: "%s", float: "%r", bool: "%s"}  # a float's repr is what json writes
_LEAF_TEXT = {str: _COMPACT.encode, bool: {True: "true", False: "false"}.__getitem__}
_CLIP_KEYS = tuple(f.key for f in CLIP_FIELDS)
_CLIP_ATTRS = tuple(f.attr for f in CLIP_FIELDS)
_FADES_AT = tuple(i for i, f in enumerate(CLIP_FIELDS) if f.kind is Fade)
_clip_values = attrgetter(*_CLIP_ATTRS)
_fade_values = attrgetter(*(f.attr for f in FADE_FIELDS))
_FADE_KEYS = tuple(f.key for f in FADE_FIELDS)


class _Line(str):
    """A value already written as one line of JSON (a clip from _clip_lines)."""


def _fade_to_json(fade: Fade) -> dict[str, Any]:
    return dict(zip(_FADE_KEYS, _fade_values(fade), strict=True))


def clip_to_json(clip: Clip) -> dict[str, Any]:
    values = list(_clip_values(clip))
    for i in _FADES_AT:
        values[i] = _fade_to_json(values[i])
    return dict(zip(_CLIP_KEYS, values, strict=True))


def _line_layout(record: type, path: str = "") -> tuple[str, list[Callable[[Iterable], Iterator]]]:
    """The record's one-line JSON as a %-template, and for each value in it a function from the
    clips to that value of each clip as JSON text or a float (its column)."""
    pieces, columns = [], []
    for f in _FIELDS[record]:
        if f.kind in _FIELDS:
            piece, more = _line_layout(f.kind, f"{path}{f.attr}.")
        else:
            piece, more = _LEAF_PIECE[f.kind], [_column(f"{path}{f.attr}", _LEAF_TEXT.get(f.kind))]
        pieces.append(f"{_COMPACT.encode(f.key)}: {piece}")
        columns += more
    return "{" + ", ".join(pieces) + "}", columns


def _column(attr: str, text: Callable[[Any], str] | None) -> Callable[[Iterable], Iterator]:
    read = attrgetter(attr)
    if text is None:
        return lambda clips: map(read, clips)
    return lambda clips: map(text, map(read, clips))


_CLIP_LINE, _CLIP_COLUMNS = _line_layout(Clip)


def _clip_lines(clips: Sequence[Clip]) -> list[_Line]:
    """Each clip's line: the same text as json's encoder gives for clip_to_json(clip)."""
    rows = zip(*(column(clips) for column in _CLIP_COLUMNS), strict=True)
    return list(map(_Line, map(_CLIP_LINE.__mod__, rows)))


def _clip_line(clip: Clip) -> _Line:
    """One clip's line (what the tests hold against json's encoder)."""
    return _clip_lines((clip,))[0]


# Reading: the fast path for clips as the editor writes them, and the field-by-field checks.
_clip_items = itemgetter(*_CLIP_KEYS)
_plain_numbers = itemgetter(*(i for i, f in enumerate(CLIP_FIELDS) if f.kind is float))
_PLAIN_TYPES = tuple(dict if f.kind is Fade else f.kind for f in CLIP_FIELDS)
_fade_items = itemgetter(*(f.key for f in FADE_FIELDS))
_PLAIN_FADE_TYPES = tuple(f.kind for f in FADE_FIELDS)
_NO_FADE = Fade()
_NO_FADE_JSON = _fade_to_json(_NO_FADE)


def _plain_clip(obj: Any) -> Clip | None:
    """A clip as the editor saves it (every field present, plain finite floats), built without
    the per-field checks; None for anything else, which _clip then checks field by field.

    Non-finite numbers are caught by one isfinite of their sum (inf or NaN if any one is; an
    overflowing sum of finite numbers only sends the clip down the slow path).
    """
    if type(obj) is not dict or len(obj) != len(CLIP_FIELDS):
        return None
    try:
        values = _clip_items(obj)
    except KeyError:
        return None
    if tuple(map(type, values)) != _PLAIN_TYPES or not math.isfinite(sum(_plain_numbers(values))):
        return None
    attrs = dict(zip(_CLIP_ATTRS, values, strict=True))
    try:
        for i in _FADES_AT:
            attrs[_CLIP_ATTRS[i]] = _plain_fade(values[i])
        return Clip.from_checked(attrs)
    except (EditError, NotPlain):
        return None


def _plain_fade(obj: dict) -> Fade:
    if obj == _NO_FADE_JSON:
        return _NO_FADE
    if len(obj) == len(FADE_FIELDS):
        try:
            values = _fade_items(obj)
        except KeyError:
            raise NotPlain from None
        if tuple(map(type, values)) == _PLAIN_FADE_TYPES:
            return Fade(*values)
    raise NotPlain


def _number(obj: Any, key: str, where: str, default: Any) -> float:
    return fields.number(obj, key, where, None if default is dataclasses.MISSING else default)


def _text_field(obj: Any, key: str, where: str, default: Any) -> str:
    if default is dataclasses.MISSING:
        return fields.get(obj, key, str, where)
    return fields.text(obj, key, where, default)


def _fade(obj: Any, key: str, where: str, default: Fade) -> Fade:
    if key not in fields.obj(obj, where):
        return default
    where = f"{where}.{key}"
    fade = fields.obj(obj[key], where)
    return built_at(lambda: _record(Fade, fade, where), where)


# How each kind of field is checked as it is read: (obj, key, where, default) -> value.
_READERS: dict[type, Callable[[Any, str, str, Any], Any]] = {
    float: _number,
    str: _text_field,
    bool: fields.flag,
    Fade: _fade,
}


def _record(record: type, obj: Any, where: str) -> Any:
    """The record (a Clip or Fade) read field by field, each malformed field a FieldError."""
    return record(
        **{f.attr: _READERS[f.kind](obj, f.key, where, f.default) for f in _FIELDS[record]}
    )


def _clip(obj: Any, where: str) -> Clip:
    return _record(Clip, obj, where)


# --- writing -----------------------------------------------------------------------------------


MediaEntry = Callable[[SampledTile], dict[str, Any]]


def _base64_entry(tile: SampledTile) -> dict[str, Any]:
    return sample_media.encode(tile.data)


def tile_to_json(tile: Tile, media: dict[str, Any], entry: MediaEntry) -> dict[str, Any]:
    if isinstance(tile, SampledTile):
        if tile.key not in media:  # a recording shared by tiles and variants is encoded once
            media[tile.key] = entry(tile)
        return {
            "type": "sampled",
            "name": tile.name,
            "rate": tile.rate,
            "source": tile.source,
            "media": tile.key,
        }
    if isinstance(tile, SplineTile):
        return {
            "type": "spline",
            "name": tile.name,
            "duration": tile.duration,
            "method": tile.method,
            "points": [list(p) for p in tile.points],
        }
    if isinstance(tile, VibrationTile):
        return tile.as_json()
    return {
        "type": "generator",
        "name": tile.name,
        "generator": tile.generator,
        "duration": tile.duration,
        "params": dict(tile.params),
    }


def _clips_to_json(clips: Sequence[Clip]) -> list[dict[str, Any]]:
    return [clip_to_json(c) for c in clips]


def track_to_json(
    track: Track, clips_json: Callable[[Sequence[Clip]], list] = _clips_to_json
) -> dict[str, Any]:
    return {
        "id": track.id,
        "kind": track.kind,
        "name": track.name,
        "gain": track.gain,
        "mute": track.mute,
        "solo": track.solo,
        "full_scale": track.full_scale,
        "clips": clips_json(track.clips),
    }


def _id_order(item_id: str) -> tuple[str, int, str]:
    """Ids like tile9 before tile10: prefix, then number, then the id itself."""
    stem = item_id.rstrip("0123456789")
    digits = item_id[len(stem) :]
    return (stem, int(digits) if digits else -1, item_id)


def to_json(
    project: Project,
    clips_json: Callable[[Sequence[Clip]], list] = _clips_to_json,
    media_entry: MediaEntry = _base64_entry,
) -> dict[str, Any]:
    """The project as a JSON-ready dict (schema SCHEMA); clips_json writes the clips of each of
    the project's own tracks (a variant's tracks are saved one line each, as plain dicts) and
    media_entry each recording's samples."""
    media: dict[str, Any] = {}

    def tiles(mapping) -> dict[str, Any]:  # in id order, so a saved file's bytes are stable
        return {
            k: tile_to_json(mapping[k], media, media_entry) for k in sorted(mapping, key=_id_order)
        }

    body = {
        "axis": project.axis,
        "rate": project.rate,
        "next_id": project.next_id,
        "metadata": dict(project.metadata),
        "tiles": tiles(project.tiles),
        "palette": [
            {"name": t.name, "role": t.role, "tiles": list(t.tile_ids)} for t in project.palette
        ],
        "tracks": [track_to_json(t, clips_json) for t in project.tracks],
        "variants": [
            {
                "name": v.name,
                "tiles": tiles(v.tiles),
                "tracks": [track_to_json(t) for t in v.tracks],  # one line per track
            }
            for v in project.variants
        ],
        "active_variant": project.active_variant,
        **markers_json(project),
    }
    return {"format": FORMAT, "schema": SCHEMA, "project": body, "media": media}


_OUTLINE_DEPTH = 5  # clips, tile points and deeper: one line each, through json's C encoder


def _text(value: Any, compact: Callable[[Any], str], depth: int = 0) -> str:
    """JSON indented by one space per level down to _OUTLINE_DEPTH, each deeper value on one line.

    json.dumps(indent=...) runs json's pure-Python encoder (8.7 s for 100,000 clips); here Python
    lays out the few outer levels, each clip is a _Line already, and compact (json's C encoder)
    writes every other deeper value.
    """
    if type(value) is _Line:
        return value
    if depth >= _OUTLINE_DEPTH or not isinstance(value, (dict, list)) or not value:
        return compact(value)
    pad, close = "\n" + " " * (depth + 1), "\n" + " " * depth
    if isinstance(value, dict):
        items = [f"{compact(str(k))}: {_text(v, compact, depth + 1)}" for k, v in value.items()]
        return "{" + pad + ("," + pad).join(items) + close + "}"
    return "[" + pad + ("," + pad).join(_text(v, compact, depth + 1) for v in value) + close + "]"


def dumps(project: Project) -> str:
    """The project as one text (the clipboard's form): its recordings as base64 inside the JSON."""
    return _dumped(to_json(project, _clip_lines))


def _dumped(doc: dict[str, Any]) -> str:
    try:
        return _text(doc, _COMPACT.encode) + "\n"
    except (TypeError, ValueError) as exc:
        raise ProjectFileError(f"the project cannot be saved: {exc}") from None


def save(project: Project, path: str | os.PathLike) -> None:
    """Write the project atomically: the old file stays intact until the new one is complete.

    The JSON document comes first; each recording's samples follow it in the binary appendix,
    written straight from the tile's array (its media entry's hash is the tile's content key,
    already known: nothing is hashed, encoded or copied).
    """
    recordings: list[np.ndarray] = []
    appendix = 0

    def raw(tile: SampledTile) -> dict[str, Any]:
        nonlocal appendix
        entry = sample_media.raw_entry(tile.data, tile.rate, tile.key, appendix)
        recordings.append(tile.data)
        appendix += entry["length"]
        return entry

    doc = to_json(project, _clip_lines, raw)
    if recordings:
        doc["appendix"] = {"bytes": appendix}
    text = _dumped(doc).encode("utf-8")

    def write(tmp: Path) -> None:
        with open(tmp, "wb") as out:
            out.write(text)
            if recordings:
                out.write(sample_media.SEPARATOR)
                for data in recordings:
                    sample_media.write_raw(data, out)

    write_atomically(path, write)


# --- reading -----------------------------------------------------------------------------------


Media = dict[str, tuple[np.ndarray, ContentKey | None]]


def tile_from_json(obj: Any, media: Media, where: str) -> Tile:
    return built_at(lambda: _tile(obj, media, where), where)


def _tile(obj: Any, media: Media, where: str) -> Tile:
    kind = fields.get(obj, "type", str, where)
    name = fields.get(obj, "name", str, where)
    if kind == "sampled":
        key = fields.get(obj, "media", str, where)
        if key not in media:
            raise FieldError(f"{where} refers to missing media {key!r}")
        rate = fields.number(obj, "rate", where, positive=True)
        data, content = media[key]
        source = fields.text(obj, "source", where, "")
        if content is None:
            return SampledTile(data, rate, name, source)
        # read raw: checked finite and hashed while read, so the tile's key costs nothing
        return SampledTile.from_checked(data, rate, name, source, content.key(rate))
    if kind == "spline":
        points = fields.get(obj, "points", list, where)
        if not all(isinstance(p, list) and len(p) == 2 for p in points):
            raise FieldError(f"{where}.points should be [time, value] pairs")
        return SplineTile(
            tuple(
                (
                    fields.as_number(t, f"{where}.points[{i}]"),
                    fields.as_number(v, f"{where}.points[{i}]"),
                )
                for i, (t, v) in enumerate(points)
            ),
            fields.number(obj, "duration", where, positive=True),
            fields.get(obj, "method", str, where),
            name,
        )
    if kind == "generator":
        params = fields.get(obj, "params", dict, where)
        return GeneratorTile(
            fields.get(obj, "generator", str, where),
            fields.number(obj, "duration", where, positive=True),
            tuple((k, fields.as_number(v, f"{where}.params.{k}")) for k, v in params.items()),
            name,
        )
    if kind == "vibration":
        return VibrationTile.from_json(obj)
    raise FieldError(f"{where} has unknown tile type {kind!r}")


def built_at(make: Callable[[], Any], where: str) -> Any:
    """make(), with a refused value (EditError) reported at `where`."""
    try:
        return make()
    except EditError as exc:
        raise FieldError(f"{where}: {exc}") from None


def clip_from_json(obj: Any, where: str) -> Clip:
    return _plain_clip(obj) or built_at(lambda: _clip(obj, where), where)


def track_from_json(obj: Any, where: str) -> Track:
    clips = fields.get(obj, "clips", list, where)
    full_scale = None
    if obj.get("full_scale") is not None:
        full_scale = fields.number(obj, "full_scale", where, positive=True)
    return Track(
        id=fields.get(obj, "id", str, where),
        kind=fields.get(obj, "kind", str, where),
        name=fields.get(obj, "name", str, where),
        clips=tuple(clip_from_json(c, f"{where}.clips[{i}]") for i, c in enumerate(clips)),
        gain=fields.number(obj, "gain", where, 1.0),
        mute=fields.flag(obj, "mute", where),
        solo=fields.flag(obj, "solo", where),
        full_scale=full_scale,
    )


def markers_from_json(body: dict) -> tuple[tuple[Marker, ...], LoopRegion | None]:
    markers = []
    for i, m in enumerate(fields.get(body, "markers", list, "project")):
        where = f"project.markers[{i}]"
        name, at = fields.get(m, "name", str, where), fields.number(m, "at", where)
        markers.append(built_at(lambda name=name, at=at: Marker(name, at), where))
    raw = body.get("loop")
    if raw is None:
        return tuple(sorted(markers, key=lambda m: m.at)), None
    if not (isinstance(raw, list) and len(raw) == 2):
        raise FieldError("project.loop should be [start, stop] or null")
    start, stop = (fields.as_number(v, "project.loop") for v in raw)
    loop = built_at(lambda: LoopRegion(start, stop), "project.loop")
    return tuple(sorted(markers, key=lambda m: m.at)), loop


def _check_references(project: Project) -> None:
    from timeline.plugins.track_kinds import track_kind

    designs = [(project.tracks, project.tiles, "the project")] + [
        (v.tracks, v.tiles, f"variant {v.name!r}") for v in project.variants
    ]
    for tracks, tiles, where in designs:
        ids = [t.id for t in tracks] + [c.id for t in tracks for c in t.clips]
        if len(ids) != len(set(ids)):
            raise FieldError(f"{where} uses one id twice")
        for track in tracks:
            kind = track_kind(track.kind)
            if project.axis not in kind.axes:
                raise FieldError(f"{where} has a {kind.id} track on the {project.axis} axis")
            for clip in track.clips:
                if clip.tile_id not in tiles:
                    raise FieldError(
                        f"clip {clip.id!r} in {where} uses missing tile {clip.tile_id!r}"
                    )
    for tab in project.palette:
        missing = [i for i in tab.tile_ids if i not in project.tiles]
        if missing:
            raise FieldError(f"palette tab {tab.name!r} lists missing tile {missing[0]!r}")


def from_json(doc: Any, appendix: sample_media.Appendix | None = None) -> Project:
    """Build a project from a parsed file (and its binary appendix, if it has one), migrating
    older schemas; FieldError if malformed."""
    if not isinstance(doc, dict) or doc.get("format") != FORMAT:
        raise FieldError("it is not a haptic-timeline project")
    version = doc.get("schema")
    if not isinstance(version, int) or isinstance(version, bool) or version < 1:
        raise FieldError("its schema version is missing")
    if version > SCHEMA:
        raise FieldError(
            f"it was written by a newer haptic-timeline (schema {version}; "
            f"this one reads up to {SCHEMA})"
        )
    while version < SCHEMA:
        doc = MIGRATIONS[version](doc)
        version += 1
    body = fields.get(doc, "project", dict, "the file")
    sample_media.check_size(appendix, doc.get("appendix"))
    media = {
        k: sample_media.samples_of(v, f"media {k!r}", appendix)
        for k, v in fields.get(doc, "media", dict, "the file").items()
    }

    def tiles(obj: Any, where: str) -> Map:
        return Map(
            {
                str(k): tile_from_json(v, media, f"{where} tile {k!r}")
                for k, v in fields.get(obj, "tiles", dict, where).items()
            }
        )

    def tracks(obj: Any, where: str) -> tuple[Track, ...]:
        return tuple(
            track_from_json(t, f"{where}.tracks[{i}]")
            for i, t in enumerate(fields.get(obj, "tracks", list, where))
        )

    variants = tuple(
        Variant(
            fields.get(v, "name", str, f"variant {i}"),
            tracks(v, f"variant {i}"),
            tiles(v, f"variant {i}"),
        )
        for i, v in enumerate(fields.get(body, "variants", list, "project"))
    )
    palette = tuple(
        PaletteTab(
            fields.get(t, "name", str, "palette tab"),
            fields.get(t, "role", str, "palette tab"),
            IdSequence(checked_tile_ids(fields.get(t, "tiles", list, "palette tab"))),
        )
        for t in fields.get(body, "palette", list, "project")
    )
    active = body.get("active_variant")
    if active is not None and not isinstance(active, str):
        raise FieldError("project.active_variant should be a name or null")
    metadata = fields.json_safe(fields.get(body, "metadata", dict, "project"), "project.metadata")
    markers, loop = markers_from_json(body)
    project = built_at(
        lambda: _project(body, tracks, tiles, palette, variants, active, metadata, markers, loop),
        "project",
    )
    _check_references(project)
    return project


def _project(
    body: dict,
    tracks: Callable[[Any, str], tuple[Track, ...]],
    tiles: Callable[[Any, str], Map],
    palette: tuple[PaletteTab, ...],
    variants: tuple[Variant, ...],
    active: str | None,
    metadata: dict,
    markers: tuple[Marker, ...],
    loop: LoopRegion | None,
) -> Project:
    return Project(
        axis=fields.get(body, "axis", str, "project"),
        rate=fields.number(body, "rate", "project", positive=True),
        tracks=tracks(body, "project"),
        tiles=tiles(body, "project"),
        palette=palette,
        variants=variants,
        active_variant=active,
        metadata=MappingProxyType(dict(metadata)),  # a copy: the document stays the caller's
        next_id=fields.integer(body, "next_id", "project", 1, fields.MAX_ID),
        markers=markers,
        loop=loop,
    )


def checked_tile_ids(items: list) -> list[str]:
    if not all(isinstance(i, str) for i in items):
        raise FieldError("a palette tab's tiles should be tile ids (text)")
    return items


def loads(text: str | bytes, name: str = "the project") -> Project:
    """Parse a project file's content: text, or a saved file's bytes (its appendix too)."""
    if isinstance(text, str):
        return _opened(lambda: from_json(_parsed(text)), name)
    return _opened(lambda: _read(io.BytesIO(text)), name)


def _parsed(text: str | bytes | bytearray) -> Any:
    return json.loads(text, parse_constant=fields.refuse_constant)


def _read(file: io.BufferedIOBase) -> Project:
    """The project of an open file: its JSON document, then its appendix's samples."""
    text, appendix = sample_media.split(file)
    doc = _parsed(text)
    del text  # let go of the JSON's bytes before the recordings are read
    return from_json(doc, appendix)


def _opened(read: Callable[[], Project], name: str) -> Project:
    """The project read(); any problem is one ProjectFileError sentence."""
    try:
        with gc_pause.paused():
            return read()
    except HapticTimelineError as exc:  # a FieldError among them
        raise ProjectFileError(f"{name} cannot be opened: {exc}") from None
    except (ValueError, UnicodeDecodeError) as exc:
        raise ProjectFileError(f"{name} is not a readable project file ({exc})") from None
    except RecursionError:
        raise ProjectFileError(f"{name} is nested too deeply to be a project file") from None


def load(path: str | os.PathLike) -> Project:
    """Read a .htl project file; any problem is one ProjectFileError sentence."""
    path = Path(path)
    if not path.exists():
        raise ProjectFileError(f"{path} does not exist")
    if path.is_dir():
        raise ProjectFileError(f"{path} is a folder, not a project file")
    size = path.stat().st_size
    if size > MAX_FILE_BYTES:
        raise ProjectFileError(f"{path} is {size} bytes, larger than a project file can be")

    def read() -> Project:
        with open(path, "rb") as file:
            return _read(file)

    return _opened(read, str(path))


def markers_json(project: Project) -> dict:
    """The markers and loop region as they are stored in a project file."""
    loop = project.loop
    return {
        "markers": [{"name": m.name, "at": m.at} for m in project.markers],
        "loop": None if loop is None else [loop.start, loop.stop],
    }
