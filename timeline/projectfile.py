"""The .htl project file: JSON with a schema version, sampled media stored losslessly inside.

Loading runs no code (plain JSON, no pickle or eval), bounds every declared size, and turns any
malformed content into one ProjectFileError sentence. Saving is atomic: a crash mid-save leaves
the previous file intact.
"""

from __future__ import annotations

import base64
import json
import os
import zlib
from collections.abc import Callable
from pathlib import Path
from types import MappingProxyType
from typing import Any

import numpy as np

from timeline.atomic import write_atomically
from timeline.errors import EditError, HapticTimelineError, ProjectFileError
from timeline.markers import LoopRegion, Marker, markers_to_json
from timeline.model import Clip, Fade, PaletteTab, Project, Track, Variant
from timeline.tiles import MAX_TILE_SAMPLES, GeneratorTile, SampledTile, SplineTile, Tile
from timeline.vibration_tile import VibrationTile

FORMAT = "haptic-timeline"
SCHEMA = 3  # 2: vibration tiles; 3: markers and the loop region
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


# Upgrade functions keyed by the schema version they read; each returns the next version's dict.
MIGRATIONS: dict[int, Callable[[dict], dict]] = {1: _schema_1_to_2, 2: _schema_2_to_3}


# --- writing -----------------------------------------------------------------------------------


def _encode_samples(data: np.ndarray) -> dict[str, Any]:
    raw = np.ascontiguousarray(data, dtype="<f8").tobytes()
    return {
        "dtype": "<f8",
        "count": int(data.size),
        "encoding": "zlib+base64",
        "data": base64.b64encode(zlib.compress(raw, 6)).decode("ascii"),
    }


def _tile_to_json(tile: Tile, media: dict[str, Any]) -> dict[str, Any]:
    if isinstance(tile, SampledTile):
        media.setdefault(tile.key, _encode_samples(tile.data))
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


def _fade_to_json(fade: Fade) -> dict[str, Any]:
    return {"length": fade.length, "shape": fade.shape}


def _clip_to_json(clip: Clip) -> dict[str, Any]:
    return {
        "id": clip.id,
        "tile": clip.tile_id,
        "start": clip.start,
        "source_in": clip.source_in,
        "source_out": clip.source_out,
        "stretch": clip.stretch,
        "stretch_mode": clip.stretch_mode,
        "loop_phase": clip.loop_phase,
        "gain": clip.gain,
        "scale": clip.scale,
        "offset": clip.offset,
        "pivot": clip.pivot,
        "reverse": clip.reverse,
        "fade_in": _fade_to_json(clip.fade_in),
        "fade_out": _fade_to_json(clip.fade_out),
    }


def _track_to_json(track: Track) -> dict[str, Any]:
    return {
        "id": track.id,
        "kind": track.kind,
        "name": track.name,
        "gain": track.gain,
        "mute": track.mute,
        "solo": track.solo,
        "full_scale": track.full_scale,
        "clips": [_clip_to_json(c) for c in track.clips],
    }


def _id_order(item_id: str) -> tuple[str, int, str]:
    """Ids like tile9 before tile10: prefix, then number, then the id itself."""
    stem = item_id.rstrip("0123456789")
    digits = item_id[len(stem) :]
    return (stem, int(digits) if digits else -1, item_id)


def to_json(project: Project) -> dict[str, Any]:
    """The project as a JSON-ready dict (schema SCHEMA)."""
    media: dict[str, Any] = {}

    def tiles(mapping) -> dict[str, Any]:  # in id order, so a saved file's bytes are stable
        return {k: _tile_to_json(mapping[k], media) for k in sorted(mapping, key=_id_order)}

    body = {
        "axis": project.axis,
        "rate": project.rate,
        "next_id": project.next_id,
        "metadata": dict(project.metadata),
        "tiles": tiles(project.tiles),
        "palette": [
            {"name": t.name, "role": t.role, "tiles": list(t.tile_ids)} for t in project.palette
        ],
        "tracks": [_track_to_json(t) for t in project.tracks],
        "variants": [
            {
                "name": v.name,
                "tiles": tiles(v.tiles),
                "tracks": [_track_to_json(t) for t in v.tracks],
            }
            for v in project.variants
        ],
        "active_variant": project.active_variant,
        **markers_to_json(project),
    }
    return {"format": FORMAT, "schema": SCHEMA, "project": body, "media": media}


_COMPACT = json.JSONEncoder(allow_nan=False, separators=(", ", ": ")).encode
_OUTLINE_DEPTH = 5  # clips, tile points and deeper: one line each, through json's C encoder


def _text(value: Any, depth: int = 0) -> str:
    """JSON indented by one space per level down to _OUTLINE_DEPTH, each deeper value on one line.

    json.dumps(indent=...) runs json's pure-Python encoder (8.7 s for 100,000 clips); here Python
    lays out the few outer levels and the C encoder writes each clip.
    """
    if depth >= _OUTLINE_DEPTH or not isinstance(value, (dict, list)) or not value:
        return _COMPACT(value)
    pad, close = "\n" + " " * (depth + 1), "\n" + " " * depth
    if isinstance(value, dict):
        items = [f"{_COMPACT(str(k))}: {_text(v, depth + 1)}" for k, v in value.items()]
        return "{" + pad + ("," + pad).join(items) + close + "}"
    return "[" + pad + ("," + pad).join(_text(v, depth + 1) for v in value) + close + "]"


def dumps(project: Project) -> str:
    """The project file's text."""
    try:
        return _text(to_json(project)) + "\n"
    except (TypeError, ValueError) as exc:
        raise ProjectFileError(f"the project cannot be saved: {exc}") from None


def save(project: Project, path: str | os.PathLike) -> None:
    """Write the project atomically: the old file stays intact until the new one is complete."""
    text = dumps(project).encode("utf-8")
    write_atomically(path, lambda tmp: tmp.write_bytes(text))


# --- reading -----------------------------------------------------------------------------------


_MISSING = object()


class _Bad(Exception):
    """Internal: the content is malformed; the message says where."""


def _get(obj: Any, key: str, kind: type | tuple[type, ...], where: str) -> Any:
    if type(obj) is dict:  # the common case first: a value of exactly the wanted type
        value = obj.get(key, _MISSING)
        if type(value) is kind:
            return value
    if not isinstance(obj, dict):
        raise _Bad(f"{where} is not an object")
    if key not in obj:
        raise _Bad(f"{where} has no {key!r}")
    value = obj[key]
    if kind is float and isinstance(value, int) and not isinstance(value, bool):
        value = float(value)
    if not isinstance(value, kind) or (kind is not bool and isinstance(value, bool)):
        names = kind.__name__ if isinstance(kind, type) else "/".join(k.__name__ for k in kind)
        raise _Bad(f"{where}.{key} should be a {names}")
    return value


def _num(obj: Any, key: str, where: str, default: float | None = None) -> float:
    if isinstance(obj, dict) and key not in obj and default is not None:
        return default
    return _get(obj, key, float, where)


def _decode_samples(entry: Any, where: str) -> np.ndarray:
    if (
        _get(entry, "dtype", str, where) != "<f8"
        or _get(entry, "encoding", str, where) != "zlib+base64"
    ):
        raise _Bad(f"{where} uses an unknown sample encoding")
    count = _get(entry, "count", int, where)
    if not 0 < count <= MAX_TILE_SAMPLES:
        raise _Bad(f"{where} declares {count} samples, outside the supported range")
    try:
        packed = base64.b64decode(_get(entry, "data", str, where), validate=True)
        inflater = zlib.decompressobj()
        raw = inflater.decompress(packed, count * 8 + 1)  # never inflate more than declared
    except (ValueError, zlib.error):
        raise _Bad(f"{where} holds damaged sample data") from None
    if len(raw) != count * 8 or inflater.unconsumed_tail or not inflater.eof:
        raise _Bad(f"{where} holds {len(raw) // 8} samples but declares {count}")
    return np.frombuffer(raw, dtype="<f8").astype(np.float64)


def _tile_from_json(obj: Any, media: dict[str, np.ndarray], where: str) -> Tile:
    kind = _get(obj, "type", str, where)
    name = _get(obj, "name", str, where)
    if kind == "sampled":
        key = _get(obj, "media", str, where)
        if key not in media:
            raise _Bad(f"{where} refers to missing media {key!r}")
        return SampledTile(media[key], _num(obj, "rate", where), name, obj.get("source", ""))
    if kind == "spline":
        points = _get(obj, "points", list, where)
        if not all(isinstance(p, list) and len(p) == 2 for p in points):
            raise _Bad(f"{where}.points should be [time, value] pairs")
        return SplineTile(
            tuple((float(t), float(v)) for t, v in points),
            _num(obj, "duration", where),
            _get(obj, "method", str, where),
            name,
        )
    if kind == "generator":
        params = _get(obj, "params", dict, where)
        if not all(
            isinstance(v, (int, float)) and not isinstance(v, bool) for v in params.values()
        ):
            raise _Bad(f"{where}.params should be numbers")
        return GeneratorTile(
            _get(obj, "generator", str, where),
            _num(obj, "duration", where),
            tuple(params.items()),
            name,
        )
    if kind == "vibration":
        return VibrationTile.from_json(obj)
    raise _Bad(f"{where} has unknown tile type {kind!r}")


def _fade_from_json(obj: Any, where: str) -> Fade:
    return Fade(_num(obj, "length", where), _get(obj, "shape", str, where))


def _clip_from_json(obj: Any, where: str) -> Clip:
    return Clip(
        id=_get(obj, "id", str, where),
        tile_id=_get(obj, "tile", str, where),
        start=_num(obj, "start", where),
        source_in=_num(obj, "source_in", where),
        source_out=_num(obj, "source_out", where),
        stretch=_num(obj, "stretch", where, 1.0),
        stretch_mode=obj.get("stretch_mode", "squeeze"),
        loop_phase=_num(obj, "loop_phase", where, 0.0),
        gain=_num(obj, "gain", where, 1.0),
        scale=_num(obj, "scale", where, 1.0),
        offset=_num(obj, "offset", where, 0.0),
        pivot=_num(obj, "pivot", where, 0.0),
        reverse=bool(obj.get("reverse", False)),
        fade_in=_fade_from_json(
            obj.get("fade_in", {"length": 0.0, "shape": "linear"}), where + ".fade_in"
        ),
        fade_out=_fade_from_json(
            obj.get("fade_out", {"length": 0.0, "shape": "linear"}), where + ".fade_out"
        ),
    )


def _track_from_json(obj: Any, where: str) -> Track:
    clips = _get(obj, "clips", list, where)
    full_scale = obj.get("full_scale") if isinstance(obj, dict) else None
    if full_scale is not None and (
        isinstance(full_scale, bool) or not isinstance(full_scale, (int, float))
    ):
        raise _Bad(f"{where}.full_scale should be a number or null")
    return Track(
        id=_get(obj, "id", str, where),
        kind=_get(obj, "kind", str, where),
        name=_get(obj, "name", str, where),
        clips=tuple(_clip_from_json(c, f"{where}.clips[{i}]") for i, c in enumerate(clips)),
        gain=_num(obj, "gain", where, 1.0),
        mute=bool(obj.get("mute", False)),
        solo=bool(obj.get("solo", False)),
        full_scale=None if full_scale is None else float(full_scale),
    )


def _markers_from_json(body: dict) -> tuple[tuple[Marker, ...], LoopRegion | None]:
    markers = []
    for i, m in enumerate(_get(body, "markers", list, "project")):
        where = f"project.markers[{i}]"
        if not isinstance(m, dict):
            raise _Bad(f"{where} should be an object")
        try:
            markers.append(Marker(_get(m, "name", str, where), _num(m, "at", where)))
        except EditError as exc:
            raise _Bad(f"{where}: {exc}") from None
    raw = body.get("loop")
    if raw is None:
        return tuple(sorted(markers, key=lambda m: m.at)), None
    if not (isinstance(raw, list) and len(raw) == 2):
        raise _Bad("project.loop should be [start, stop] or null")
    try:
        loop = LoopRegion(*(float(v) for v in raw))
    except (TypeError, ValueError, EditError) as exc:
        raise _Bad(f"project.loop: {exc}") from None
    return tuple(sorted(markers, key=lambda m: m.at)), loop


def _check_references(project: Project) -> None:
    from timeline.kinds import track_kind

    designs = [(project.tracks, project.tiles, "the project")] + [
        (v.tracks, v.tiles, f"variant {v.name!r}") for v in project.variants
    ]
    for tracks, tiles, where in designs:
        ids = [t.id for t in tracks] + [c.id for t in tracks for c in t.clips]
        if len(ids) != len(set(ids)):
            raise _Bad(f"{where} uses one id twice")
        for track in tracks:
            kind = track_kind(track.kind)
            if project.axis not in kind.axes:
                raise _Bad(f"{where} has a {kind.id} track on the {project.axis} axis")
            for clip in track.clips:
                if clip.tile_id not in tiles:
                    raise _Bad(f"clip {clip.id!r} in {where} uses missing tile {clip.tile_id!r}")
    for tab in project.palette:
        missing = [i for i in tab.tile_ids if i not in project.tiles]
        if missing:
            raise _Bad(f"palette tab {tab.name!r} lists missing tile {missing[0]!r}")


def from_json(doc: Any) -> Project:
    """Build a project from a parsed file, migrating older schemas; raises _Bad if malformed."""
    if not isinstance(doc, dict) or doc.get("format") != FORMAT:
        raise _Bad("it is not a haptic-timeline project")
    version = doc.get("schema")
    if not isinstance(version, int) or isinstance(version, bool) or version < 1:
        raise _Bad("its schema version is missing")
    if version > SCHEMA:
        raise _Bad(
            f"it was written by a newer haptic-timeline (schema {version}; "
            f"this one reads up to {SCHEMA})"
        )
    while version < SCHEMA:
        doc = MIGRATIONS[version](doc)
        version += 1
    body = _get(doc, "project", dict, "the file")
    media = {
        k: _decode_samples(v, f"media {k!r}")
        for k, v in _get(doc, "media", dict, "the file").items()
    }

    def tiles(obj: Any, where: str) -> MappingProxyType:
        return MappingProxyType(
            {
                str(k): _tile_from_json(v, media, f"{where} tile {k!r}")
                for k, v in _get(obj, "tiles", dict, where).items()
            }
        )

    def tracks(obj: Any, where: str) -> tuple[Track, ...]:
        return tuple(
            _track_from_json(t, f"{where}.tracks[{i}]")
            for i, t in enumerate(_get(obj, "tracks", list, where))
        )

    variants = tuple(
        Variant(
            _get(v, "name", str, f"variant {i}"),
            tracks(v, f"variant {i}"),
            tiles(v, f"variant {i}"),
        )
        for i, v in enumerate(_get(body, "variants", list, "project"))
    )
    palette = tuple(
        PaletteTab(
            _get(t, "name", str, "palette tab"),
            _get(t, "role", str, "palette tab"),
            tuple(str(i) for i in _get(t, "tiles", list, "palette tab")),
        )
        for t in _get(body, "palette", list, "project")
    )
    active = body.get("active_variant")
    if active is not None and not isinstance(active, str):
        raise _Bad("project.active_variant should be a name or null")
    metadata = _get(body, "metadata", dict, "project")
    markers, loop = _markers_from_json(body)
    project = Project(
        axis=_get(body, "axis", str, "project"),
        rate=_num(body, "rate", "project"),
        tracks=tracks(body, "project"),
        tiles=tiles(body, "project"),
        palette=palette,
        variants=variants,
        active_variant=active,
        metadata=metadata,
        next_id=_get(body, "next_id", int, "project"),
        markers=markers,
        loop=loop,
    )
    _check_references(project)
    return project


def loads(text: str | bytes, name: str = "the project") -> Project:
    """Parse a project file's content."""
    try:
        doc = json.loads(text)
        return from_json(doc)
    except _Bad as exc:
        raise ProjectFileError(f"{name} cannot be opened: {exc}") from None
    except HapticTimelineError as exc:
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
    return loads(path.read_bytes(), str(path))
