"""A video editor's OTIO timeline as context: its sound on audio tracks and its markers, aligned.

A cut from Premiere, Resolve or any OTIO tool carries no haptics; what a designer needs from it
is where things happen. Each audio track becomes an audio (context) track (a disabled one muted),
heard and seen beside the haptics but never felt; each enabled clip is placed at its time in the
edit (clips inside nested stacks too), cut to its track's trimmed range, and plays its part of
the medium: the clip's source range less the medium's own start (media often start at a
timecode such as 01:00:00:00). Media are found from `target_url` (a file URL, an absolute path,
or a path relative to the .otio's folder), else by name in that folder or its media/. A medium
found nowhere, or not a sound file libsndfile reads, becomes a silent clip of the same span and
name, with a note, so the edit's shape stays. Markers of the timeline, its tracks and its clips
become project markers at their times in the edit, and so does each cut of a picture track
(named after its shot); pictures themselves are left out.
"""

from __future__ import annotations

import math
import re
from pathlib import Path
from typing import Any

import opentimelineio as otio

from timeline.errors import HapticTimelineError
from timeline.model.markers import Marker
from timeline.plugins.file_formats import FormatError, Imported, Placement, TrackInfo, all_formats
from timeline.tiles import GeneratorTile, Tile

AUDIO = "audio"
MAX_EDIT_SECONDS = 24 * 3600.0  # what lies beyond a day of edit is left out (noted)


class _Media:
    """Sound files read once each, by path; what could not be read, for the notes."""

    def __init__(self, folder: Path) -> None:
        self.folder = folder
        self.tiles: dict[Path, Tile | None] = {}
        self.missing: list[str] = []
        self._silent: dict[tuple[str, float], Tile] = {}
        self.disabled = 0  # audio clips switched off in the edit, left out

    def silent(self, name: str, length: float) -> Tile:
        """A silent stand-in for a clip whose medium cannot be read (one per name and length)."""
        key = (name, length)
        if key not in self._silent:
            self._silent[key] = GeneratorTile("constant", length, (("value", 0.0),), name)
        return self._silent[key]

    def path(self, reference: Any) -> Path | None:
        """The file a media reference names: its path (relative ones against the .otio's
        folder), else a file of the same name in that folder or its media/ (where a cut sent
        with its media keeps them; the editor's own path, D:/media/..., is elsewhere)."""
        url = getattr(reference, "target_url", None)
        if not isinstance(url, str) or not url.strip():
            return None
        if "://" in url and not url.startswith("file:"):
            return None  # a stream or web address: not a local file
        try:
            if url.startswith("file:"):
                url = otio.url_utils.filepath_from_url(url)
            path = Path(url)
            name = re.split(r"[\\/]", url)[-1]
            for candidate in (
                path if path.is_absolute() else self.folder / path,
                self.folder / name,
                self.folder / "media" / name,
            ):
                if candidate.is_file():
                    return candidate.resolve()  # one key per file, however it is named
        except (OSError, RuntimeError, ValueError):  # a link loop, a NUL in the name
            pass
        return None

    def tile(self, clip: otio.schema.Clip) -> Tile | None:
        path = self.path(clip.media_reference)
        if path is None:
            self.missing.append(_url_name(clip))
            return None
        if path not in self.tiles:
            self.tiles[path] = _sound(path)
        if self.tiles[path] is None:
            self.missing.append(path.name)
        return self.tiles[path]


def _url_name(clip: otio.schema.Clip) -> str:
    url = getattr(clip.media_reference, "target_url", None)
    if isinstance(url, str) and url.strip():
        return re.split(r"[\\/]", url.rstrip("/\\"))[-1] or url
    return clip.name or "an unnamed clip"


def _sound(path: Path) -> Tile | None:
    """The sound in a file, or None when it is missing or not a sound file."""
    fmt = all_formats().get("audio")
    try:
        if fmt is None or path.suffix.lower() not in fmt.extensions:
            return None
        result = fmt.read(path)
    except (HapticTimelineError, OSError, ValueError):
        return None
    return result if isinstance(result, Tile) else None


def _seconds(time: otio.opentime.RationalTime) -> float:
    return float(time.to_seconds())


def _placements(
    timeline: otio.schema.Timeline, media: _Media, notes: list[str]
) -> tuple[list[Placement], list[TrackInfo]]:
    placements: list[Placement] = []
    infos: list[TrackInfo] = []
    for number, track in enumerate(_tracks(timeline, "Audio"), start=1):
        key = f"otio-audio-{number}"
        name = track.name.strip() or f"A{number}"
        infos.append(TrackInfo(key, name, AUDIO, 1.0, not track.enabled))
        try:
            end = min(_seconds(track.trimmed_range().duration), MAX_EDIT_SECONDS)
        except Exception:  # OTIO raises its own errors when a child has no range at all
            notes.append(f"audio track {name!r} has a clip with no time range and was left out")
            continue
        for clip in track.find_clips():
            if not clip.enabled:
                media.disabled += 1
                continue
            placement = _placement(clip, timeline, (key, end), media, notes)
            if placement is not None:
                placements.append(placement)
    return placements, infos


def _placement(
    clip: otio.schema.Clip,
    timeline: otio.schema.Timeline,
    track: tuple[str, float],
    media: _Media,
    notes: list[str],
) -> Placement | None:
    """An audio clip at its time in the edit, playing its part of its medium; the part outside
    its track's trimmed range (before 0 or after the track's end) is cut off."""
    key, end = track
    try:
        trimmed = clip.trimmed_range()
        span = clip.transformed_time_range(trimmed, timeline.tracks)
    except Exception:  # OTIO raises its own errors for a clip with no range at all
        notes.append(f"audio clip {clip.name!r} has no time range and was left out")
        return None
    start, stop = _seconds(span.start_time), _seconds(span.end_time_exclusive())
    lo, hi = max(start, 0.0), min(stop, end)
    if not (math.isfinite(lo) and math.isfinite(hi)) or hi <= lo:
        notes.append(f"audio clip {clip.name!r} lies outside the edit and was left out")
        return None
    skip, start, length = lo - start, lo, hi - lo
    tile = media.tile(clip)
    if tile is None:
        silent = media.silent(clip.name or "audio", length)
        return Placement(silent, start, AUDIO, key, {})  # a plain dict: the result is pickled
    available = getattr(clip.media_reference, "available_range", None)
    origin = _seconds(available.start_time) if available is not None else 0.0
    source_in = max(0.0, _seconds(trimmed.start_time) - origin + skip)
    source_out = min(tile.duration, source_in + length)
    if source_out <= source_in:
        notes.append(f"audio clip {clip.name!r} starts past the end of its medium; left out")
        return None
    fields = {"source_in": source_in, "source_out": source_out}
    return Placement(tile, start, AUDIO, key, fields)


def _markers(timeline: otio.schema.Timeline) -> list[Marker]:
    """Markers of the timeline's stack, its tracks and every item, at their times in the edit."""
    found: list[Marker] = []
    for item in [timeline.tracks, *timeline.tracks.find_children()]:
        for marker in getattr(item, "markers", ()):
            at = _at(item, marker.marked_range.start_time, timeline)
            if at is not None:
                label = marker.name.strip() or f"{marker.color or 'marker'}".lower()
                found.append(Marker(label, at))
    return found


def _cuts(timeline: otio.schema.Timeline) -> list[Marker]:
    """Where each shot of an enabled picture track starts, named after the shot."""
    cuts: dict[tuple[str, float], Marker] = {}
    for track in _tracks(timeline, "Video"):
        for clip in track.find_clips():
            if not clip.enabled:
                continue
            at = _at(clip, _start(clip), timeline)
            if at is not None:
                label = clip.name.strip() or "cut"
                cuts.setdefault((label, at), Marker(label, at))
    return list(cuts.values())


def _start(item: Any) -> otio.opentime.RationalTime:
    return item.trimmed_range().start_time


def _at(
    item: Any, time: otio.opentime.RationalTime, timeline: otio.schema.Timeline
) -> float | None:
    """A time of an item in the edit's seconds, or None when OTIO cannot place it (or before 0)."""
    try:
        at = _seconds(item.transformed_time(time, timeline.tracks))
    except Exception:  # OTIO raises its own errors for an item with no range
        return None
    return at if math.isfinite(at) and 0 <= at <= MAX_EDIT_SECONDS else None


def _tracks(timeline: otio.schema.Timeline, kind: str) -> list[otio.schema.Track]:
    return [t for t in timeline.tracks if isinstance(t, otio.schema.Track) and t.kind == kind]


def read_context(
    timeline: otio.schema.Timeline, path: Path, folder: Path | None = None
) -> Imported:
    """A foreign timeline's sound, markers and cuts (FormatError when it has none of them);
    relative media resolve against `folder` (default: the file's own)."""
    notes: list[str] = []
    media = _Media(path.parent if folder is None else folder)
    placements, infos = _placements(timeline, media, notes)
    markers = _markers(timeline)
    cuts = _cuts(timeline)
    if not placements and not markers and not cuts:
        why = f" ({notes[0]})" if notes else ""
        raise FormatError(
            f"{path.name} was not written by haptic-timeline and holds no audio clips, markers "
            f"or cuts to design against{why}"
        )
    if media.missing:
        names = sorted(set(media.missing))
        more = f" and {len(names) - 3} more" if len(names) > 3 else ""
        notes.append(
            f"{len(media.missing)} audio clip(s) placed silent: their media were not found or "
            f"are not sound files ({', '.join(names[:3])}{more})"
        )
    if media.disabled:
        notes.append(f"{media.disabled} audio clip(s) disabled in the edit left out")
    if cuts:
        notes.append(f"{len(cuts)} picture cut(s) placed as markers named after their shots")
    found = sorted([*markers, *cuts], key=lambda m: m.at)
    return Imported(
        tuple(placements), tuple(infos), tuple(notes), tuple((m.name, m.at) for m in found)
    )
