"""OpenTimelineIO (.otio, .otioz): each track and clip with its timing, beside video and audio.

The timeline is named after the project (its title, else the file's name). Each project track
becomes one OTIO Audio track, or several ("lanes") when its clips overlap, since OTIO tracks play
clips one after another. On the time axis each track is also rendered as `<name>-<track>.wav`
(float, at the project's rate) and, for a drive track, `<name>-<track>.haptic`, beside the .otio
or inside the .otioz bundle (importers.otio_bundle); every clip points at them with
ExternalReferences (the WAV as its default media, the .haptic as a second reference named
"haptic"), its source range being its span on the timeline, exact at the project's rate or in
whole frames at a video rate (importers.otio_time). Our exact clip fields, track settings and
tiles (sampled data base64-encoded) are kept in `metadata["haptic_timeline"]`, which is what
reading our files uses (strictly: importers.otio_fields). A video editor's timeline has no such
metadata and imports as context: its sound, markers and cuts (importers.otio_context).
"""

from __future__ import annotations

import base64
import re
from dataclasses import asdict, fields, replace
from pathlib import Path
from typing import Any

import numpy as np
import opentimelineio as otio

from importers import otio_fields
from importers.otio_bundle import MediaStore, opened, write_bundle
from importers.otio_context import read_context
from importers.otio_time import Clock, video_rate
from timeline.errors import EditError, HapticTimelineError
from timeline.files import crash_isolation, exporting
from timeline.model import Clip, Project, Track
from timeline.plugins.file_formats import FormatError, Imported, Placement, Progress, TrackInfo
from timeline.signal.render_presets import preset
from timeline.tiles import GeneratorTile, SampledTile, SplineTile, Tile
from timeline.tiles.vibration_tile import VibrationTile

KEY = "haptic_timeline"
DEFAULT = "DEFAULT_MEDIA"  # OTIO's key for a clip's default media reference
VERSION = 1
_CLIP_FIELDS = [f.name for f in fields(Clip) if f.name not in ("id", "tile_id", "start")]


def encode_tile(tile: Tile) -> dict[str, Any]:
    """A tile as JSON-safe data (sampled samples exactly, as base64 little-endian float64)."""
    if isinstance(tile, SampledTile):
        raw = np.ascontiguousarray(tile.data, dtype="<f8").tobytes()
        return {
            "type": "sampled",
            "rate": tile.rate,
            "name": tile.name,
            "source": tile.source,
            "samples": base64.b64encode(raw).decode("ascii"),
        }
    if isinstance(tile, VibrationTile):
        return tile.as_json()
    if isinstance(tile, SplineTile):
        return {
            "type": "spline",
            "points": [list(p) for p in tile.points],
            "duration": tile.duration,
            "method": tile.method,
            "name": tile.name,
        }
    return {
        "type": "generator",
        "generator": tile.generator,
        "duration": tile.duration,
        "params": dict(tile.params),
        "name": tile.name,
    }


def decode_tile(data: Any) -> Tile:
    """The tile encoded by encode_tile, or a FormatError."""
    try:
        kind = data["type"]
        if not isinstance(data.get("name", ""), str):
            raise EditError(f"a tile's name must be text, not {data['name']!r}")
        if kind == "sampled":
            raw = base64.b64decode(data["samples"], validate=True)
            samples = np.frombuffer(raw, dtype="<f8")
            return SampledTile(samples, data["rate"], data["name"], data.get("source", ""))
        if kind == "spline":
            points = tuple((float(t), float(v)) for t, v in data["points"])
            return SplineTile(points, data["duration"], data["method"], data["name"])
        if kind == "generator":
            params = tuple((str(k), float(v)) for k, v in dict(data["params"]).items())
            return GeneratorTile(data["generator"], data["duration"], params, data["name"])
        if kind == "vibration":
            return VibrationTile.from_json(_plain(data))
    except HapticTimelineError as exc:
        raise FormatError(f"a tile in the OTIO file is invalid: {exc}") from None
    except (KeyError, TypeError, ValueError, AttributeError) as exc:
        raise FormatError(f"a tile in the OTIO file is malformed ({type(exc).__name__})") from None
    raise FormatError(f"a tile in the OTIO file has an unknown type {kind!r}")


def _plain(value: Any) -> Any:
    """OTIO's metadata containers as plain dicts, lists and numbers."""
    if isinstance(value, str):
        return value
    if hasattr(value, "items"):
        return {str(k): _plain(v) for k, v in value.items()}
    if hasattr(value, "__iter__"):
        return [_plain(v) for v in value]
    return value


def _lanes(track: Track) -> list[list[Clip]]:
    """Clips split into lanes in which no two overlap (first fit, by start)."""
    lanes: list[list[Clip]] = []
    for clip in sorted(track.clips, key=lambda c: c.start):
        for lane in lanes:
            if lane[-1].end <= clip.start:
                lane.append(clip)
                break
        else:
            lanes.append([clip])
    return lanes or [[]]


def _file_part(text: str) -> str:
    return re.sub(r"[^0-9A-Za-z._-]+", "_", text).strip("._") or "track"


def _media(
    project: Project, track: Track, stem: str, store: MediaStore, clock: Clock
) -> dict[str, otio.schema.ExternalReference]:
    """Render one track as a WAV (and a .haptic for drive) into the store; references to them."""
    if project.axis != "time" or not track.clips:
        return {}
    alone = replace(project, tracks=(replace(track, mute=False, solo=False),))
    stem = f"{stem}-{_file_part(track.name)}"
    available = otio.opentime.TimeRange(clock.at(0.0), clock.whole(alone.duration))
    wav = store.path(stem + ".wav")
    exporting.write_layers(exporting.project_layers(alone), wav)
    refs = {DEFAULT: otio.schema.ExternalReference(store.url(wav), available_range=available)}
    if track.kind == "drive":
        haptic = store.path(stem + ".haptic")
        exporting.export_project(alone, haptic)
        refs["haptic"] = otio.schema.ExternalReference(store.url(haptic), available_range=available)
    return refs


def _clip_fields(clip: Clip) -> dict[str, Any]:
    out = {name: getattr(clip, name) for name in _CLIP_FIELDS}
    out["fade_in"], out["fade_out"] = asdict(clip.fade_in), asdict(clip.fade_out)
    return out


def _timeline(
    source: Project, target: Path, store: MediaStore, clock: Clock
) -> otio.schema.Timeline:
    """The project as an OTIO timeline; its tracks' media rendered into the store."""
    title = source.metadata.get("title")
    timeline = otio.schema.Timeline(name=title if isinstance(title, str) and title else target.stem)
    used = {c.tile_id for t in source.tracks for c in t.clips}
    timeline.metadata[KEY] = {
        "version": VERSION,
        "axis": source.axis,
        "rate": source.rate,
        "tiles": {tid: encode_tile(source.tile(tid)) for tid in sorted(used)},
    }
    for track in source.tracks:
        media = _media(source, track, target.stem, store, clock)
        for lane_index, lane in enumerate(_lanes(track)):
            out = otio.schema.Track(name=track.name, kind=otio.schema.TrackKind.Audio)
            out.metadata[KEY] = {
                "track": track.id,
                "lane": lane_index,
                "kind": track.kind,
                "name": track.name,
                "gain": track.gain,
                "mute": track.mute,
                "solo": track.solo,
            }
            cursor = 0.0
            for clip in lane:
                if clip.start > cursor:
                    out.append(otio.schema.Gap(duration=clock.span(cursor, clip.start)))
                item = otio.schema.Clip(
                    name=source.tile(clip.tile_id).name,
                    media_reference=otio.schema.MissingReference(),
                    source_range=otio.opentime.TimeRange(
                        clock.at(clip.start if media else clip.source_in),
                        clock.span(clip.start, clip.end),
                    ),
                )
                if media:
                    item.set_media_references({k: v.clone() for k, v in media.items()}, DEFAULT)
                item.metadata[KEY] = {
                    "tile": clip.tile_id,
                    "start": clip.start,
                    **_clip_fields(clip),
                }
                out.append(item)
                cursor = clip.end
            timeline.tracks.append(out)
    if clock.frames:  # editorial adapters hang audio on a picture track: an empty one, a frame
        # longer than the design so that a clip rounded to 0 frames at its end still lies on it
        picture = otio.schema.Track(name="Picture", kind=otio.schema.TrackKind.Video)
        length = clock.span(0.0, source.duration) + otio.opentime.RationalTime(1, clock.rate)
        picture.append(otio.schema.Gap(duration=length))
        timeline.tracks.insert(0, picture)
    return timeline


class OtioFormat:
    """OpenTimelineIO: writes every track and clip; reads back files this program wrote, and a
    video editor's timeline as context."""

    name = "otio"
    extensions = (".otio", ".otioz")
    reads = "design"
    writes = "project"
    options = ()

    def write(self, source: Project, path: Path, **options: Any) -> None:
        """Write the project's tracks as OTIO tracks, with our fields in metadata, and each
        track's rendered media beside the file (.otio) or inside the bundle (.otioz)."""
        asked = options.get("rate")
        clock = Clock(source.rate, False) if asked is None else Clock(video_rate(asked), True)
        target = Path(options.get("target", path))
        if target.suffix.lower() == ".otioz":
            with MediaStore.bundled() as store:
                timeline = _timeline(source, target, store, clock)
                write_bundle(timeline, store, path)
            return
        timeline = _timeline(source, target, MediaStore(target.parent), clock)
        otio.adapters.write_to_file(timeline, str(path), adapter_name="otio_json")

    def read(
        self, path: Path, *, progress: Progress | None = None, **options: Any
    ) -> Imported | None:
        """Read back the tracks and clips of an OTIO file this program wrote.

        The file is parsed in a child process: a damaged file can crash opentimelineio.
        """
        path = Path(path)
        imported = crash_isolation.run(_read, path, what=path.name)
        if progress is not None:
            progress(1.0)
        return imported


def _renderable(tile: Tile, rate: float, name: str) -> Tile:
    """The tile, once its first samples at the design's rate render as finite numbers: a tile
    that cannot render would make every later render, play, export and check of the project
    fail, so it is refused here instead."""
    try:
        with np.errstate(all="ignore"):
            probe = tile.render(0.0, 1.0 / rate, 16, preset("normal"))
        ok = bool(np.all(np.isfinite(probe)))
    except (ArithmeticError, ValueError, MemoryError, HapticTimelineError) as exc:
        raise FormatError(
            f"tile {tile.name!r} in {name} cannot be rendered ({type(exc).__name__}): its "
            "parameters have no meaning"
        ) from None
    if not ok:
        raise FormatError(f"tile {tile.name!r} in {name} renders to values that are not numbers")
    return tile


def _ours(timeline: otio.schema.Timeline) -> bool:
    """Whether this program wrote the timeline (its metadata holds our tiles)."""
    meta = timeline.metadata.get(KEY)
    return meta is not None and "tiles" in meta


def _read(path: Path) -> Imported:
    """The tracks and clips of an OTIO file (run in a child process by OtioFormat.read): ours
    exactly, a video editor's as context (importers.otio_context)."""
    with opened(path, wants_media=lambda timeline: not _ours(timeline)) as (timeline, folder):
        meta = timeline.metadata.get(KEY)
        if not _ours(timeline):
            return read_context(timeline, path, folder)
    try:
        encoded = dict(meta["tiles"])
    except (TypeError, ValueError):
        raise FormatError(f"the tiles in {path.name} are not a table of tiles") from None
    rate = otio_fields.number(meta.get("rate"), f"the rate in {path.name}")
    tiles = {str(k): _renderable(decode_tile(v), rate, path.name) for k, v in encoded.items()}
    axis = meta.get("axis", "time")
    placements: list[Placement] = []
    infos: dict[str, TrackInfo] = {}
    for track in timeline.tracks:
        tmeta = track.metadata.get(KEY)
        if tmeta is None:
            continue
        info = otio_fields.track_info(tmeta, path.name)
        infos.setdefault(info.key, info)
        for item in track:
            cmeta = item.metadata.get(KEY) if isinstance(item, otio.schema.Clip) else None
            if cmeta is not None:
                placements.append(_placement(cmeta, tiles, info, axis, path.name))
    if not placements:
        raise FormatError(f"{path.name} holds no haptic clips")
    return Imported(tuple(placements), tuple(infos.values()))


def _placement(
    meta: Any, tiles: dict[str, Tile], track: TrackInfo, axis: str, name: str
) -> Placement:
    try:
        tile = tiles[str(meta["tile"])]
    except (KeyError, TypeError):
        raise FormatError(f"a clip in {name} names a tile the file does not hold") from None
    fields = otio_fields.clip_fields(meta, name)
    start = otio_fields.start(meta, name, axis)
    try:
        Clip("check", "check", start, **fields)  # the clip's own rules, before any project sees it
    except HapticTimelineError as exc:
        raise FormatError(f"a clip in {name} is invalid: {exc}") from None
    return Placement(tile, start, track.kind, track.key, fields)


FORMAT = OtioFormat()
