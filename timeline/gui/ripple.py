"""Ripple edit (a mode, Edit > Ripple edit): moving a clip, trimming its end or deleting clips
moves the later clips of the same track by as much, so the gaps stay as they were (Qt-free)."""

from __future__ import annotations

from collections.abc import Iterable

from timeline import edits
from timeline.model import Project

EPS = 1e-12


def later_clips(
    project: Project, track_id: str, at: float, exclude: Iterable[str] = ()
) -> list[str]:
    """The clips of a track that start at or after `at` (the excluded ones aside)."""
    skip = set(exclude)
    track = project.track(track_id)
    return [c.id for c in track.clips if c.start >= at - EPS and c.id not in skip]


def followers(project: Project, clip_ids: Iterable[str]) -> list[str]:
    """The clips that follow moved clips in ripple mode: on each track holding moved clips, the
    others that start at or after the earliest end of a moved clip there (linear in clips)."""
    ids = set(clip_ids)
    ends: dict[str, float] = {}
    for clip_id in ids:
        track, clip = project.find_clip(clip_id)
        ends[track.id] = min(ends.get(track.id, clip.end), clip.end)
    return [c for track_id, end in ends.items() for c in later_clips(project, track_id, end, ids)]


def trim_end_rippled(project: Project, clip_id: str, end: float) -> Project:
    """Trim a clip's end; the later clips of its track follow the end."""
    track, clip = project.find_clip(clip_id)
    later = later_clips(project, track.id, clip.end, [clip_id])
    project = edits.trim_clip(project, clip_id, end=end)
    return edits.shift_clips(project, later, project.find_clip(clip_id)[1].end - clip.end)


def remove_rippled(project: Project, clip_ids: Iterable[str]) -> Project:
    """Remove clips; each later clip of their tracks moves back by the length removed before it."""
    ids = set(clip_ids)
    shifts: dict[str, float] = {}
    for clip_id in ids:
        track, clip = project.find_clip(clip_id)
        for other in later_clips(project, track.id, clip.end, ids):
            shifts[other] = shifts.get(other, 0.0) - clip.duration
    project = edits.remove_clips(project, ids)
    for other, shift in shifts.items():
        project = edits.shift_clips(project, [other], shift)
    return project
