"""A video editor's OTIO timeline as context: its sound on audio tracks and its markers, aligned.

A cut from Premiere, Resolve or any OTIO tool carries no haptics; what a designer needs from it
is where things happen. Each enabled audio track becomes an audio (context) track, heard and
seen beside the haptics but never felt; each of its clips is placed at its time in the edit
(clips inside nested stacks too) and plays its part of the medium: the clip's source range less
the medium's own start (media often start at a timecode such as 01:00:00:00). Media are found
from `target_url`: a file URL, an absolute path, or a path relative to the .otio's folder. A
medium that is missing or not a sound file libsndfile reads becomes a silent clip of the same
span and name, with a note, so the edit's shape stays. Markers of the timeline, its tracks and
its clips become project markers at their times in the edit. Pictures are left out (noted).
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import opentimelineio as otio

from timeline.errors import HapticTimelineError
from timeline.model.markers import Marker
from timeline.plugins.file_formats import FormatError, Imported, Placement, TrackInfo, all_formats
from timeline.tiles import GeneratorTile, Tile

AUDIO = "audio"


class _Media:
    """Sound files read once each, by path; what could not be read, for the notes."""

    def __init__(self, folder: Path) -> None:
        self.folder = folder
        self.tiles: dict[Path, Tile | None] = {}
        self.missing: list[str] = []

    def path(self, reference: Any) -> Path | None:
        """The file a media reference names, relative ones against the .otio's folder."""
        url = getattr(reference, "target_url", None)
        if not isinstance(url, str) or not url.strip():
            return None
        if url.startswith("file:"):
            url = otio.url_utils.filepath_from_url(url)
        elif "://" in url:
            return None  # a stream or web address: not a local file
        path = Path(url)
        return path if path.is_absolute() else self.folder / path

    def tile(self, clip: otio.schema.Clip) -> Tile | None:
        path = self.path(clip.media_reference)
        if path is None:
            self.missing.append(clip.name or "an unnamed clip")
            return None
        if path not in self.tiles:
            self.tiles[path] = _sound(path)
        if self.tiles[path] is None:
            self.missing.append(path.name)
        return self.tiles[path]


def _sound(path: Path) -> Tile | None:
    """The sound in a file, or None when it is missing or not a sound file."""
    fmt = all_formats().get("audio")
    if fmt is None or path.suffix.lower() not in fmt.extensions or not path.is_file():
        return None
    try:
        result = fmt.read(path)
    except (HapticTimelineError, OSError):
        return None
    return result if isinstance(result, Tile) else None


def _seconds(time: otio.opentime.RationalTime) -> float:
    return float(time.to_seconds())


def _placements(
    timeline: otio.schema.Timeline, media: _Media, notes: list[str]
) -> tuple[list[Placement], list[TrackInfo]]:
    placements: list[Placement] = []
    infos: list[TrackInfo] = []
    audio = [t for t in timeline.tracks if isinstance(t, otio.schema.Track) and t.kind == "Audio"]
    for number, track in enumerate(audio, start=1):
        key = f"otio-audio-{number}"
        name = track.name.strip() or f"A{number}"
        infos.append(TrackInfo(key, name, AUDIO, 1.0, not track.enabled))
        for clip in track.find_clips():
            placement = _placement(clip, timeline, key, media, notes)
            if placement is not None:
                placements.append(placement)
    return placements, infos


def _placement(
    clip: otio.schema.Clip, timeline: otio.schema.Timeline, key: str, media: _Media, notes: list
) -> Placement | None:
    """An audio clip at its time in the edit, playing its part of its medium."""
    try:
        trimmed = clip.trimmed_range()
        span = clip.transformed_time_range(trimmed, timeline.tracks)
    except Exception:  # OTIO raises its own errors for a clip with no range at all
        notes.append(f"audio clip {clip.name!r} has no time range and was left out")
        return None
    start, length = _seconds(span.start_time), _seconds(span.duration)
    if not (math.isfinite(start) and math.isfinite(length)) or length <= 0 or start < 0:
        notes.append(f"audio clip {clip.name!r} lies outside the edit and was left out")
        return None
    tile = media.tile(clip)
    if tile is None:
        silent = GeneratorTile("constant", length, (("value", 0.0),), clip.name or "audio")
        return Placement(silent, start, AUDIO, key)
    available = getattr(clip.media_reference, "available_range", None)
    origin = _seconds(available.start_time) if available is not None else 0.0
    source_in = max(0.0, _seconds(trimmed.start_time) - origin)
    source_out = min(tile.duration, source_in + length)
    if source_out <= source_in:
        notes.append(f"audio clip {clip.name!r} starts past the end of its medium; left out")
        return None
    fields = {"source_in": source_in, "source_out": source_out}
    return Placement(tile, start, AUDIO, key, fields)


def _markers(timeline: otio.schema.Timeline) -> list[Marker]:
    """Markers of the timeline's stack, its tracks and every item, at their times in the edit."""
    found: list[Marker] = []
    items = [timeline.tracks, *timeline.tracks.find_children()]
    for item in items:
        for marker in getattr(item, "markers", ()):
            try:
                at = _seconds(
                    item.transformed_time(marker.marked_range.start_time, timeline.tracks)
                )
            except Exception:  # a marker on an item OTIO cannot place in time
                continue
            if math.isfinite(at) and at >= 0:
                label = marker.name.strip() or f"{marker.color or 'marker'}".lower()
                found.append(Marker(label, at))
    return sorted(found, key=lambda m: m.at)


def read_context(timeline: otio.schema.Timeline, path: Path) -> Imported:
    """A foreign timeline's sound and markers (FormatError when it has neither)."""
    notes: list[str] = []
    media = _Media(path.parent)
    placements, infos = _placements(timeline, media, notes)
    markers = _markers(timeline)
    if not placements and not markers:
        raise FormatError(
            f"{path.name} was not written by haptic-timeline and holds no audio clips or markers "
            "to design against"
        )
    if media.missing:
        shown = ", ".join(sorted(set(media.missing))[:3])
        more = len(set(media.missing)) - 3
        notes.append(
            f"{len(media.missing)} audio clip(s) placed silent: their media were not found or "
            f"are not sound files ({shown}{f' and {more} more' if more > 0 else ''})"
        )
    pictures = sum(
        1
        for t in timeline.tracks
        if isinstance(t, otio.schema.Track) and t.kind == "Video"
        for _ in t.find_clips()
    )
    if pictures:
        notes.append(f"{pictures} video clip(s) left out: pictures are not shown")
    return Imported(tuple(placements), tuple(infos), tuple(notes), tuple(markers))
