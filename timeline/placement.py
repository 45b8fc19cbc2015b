"""Where a clip of some length fits on a track without covering another clip (Qt-free).

Duplicate, paste and import use it so that new material lands in a gap rather than on top of
what is there; when the track has no room before `limit`, the caller decides what to do.
"""

from __future__ import annotations

from collections.abc import Iterable

from timeline import edits
from timeline.model import Project

EPS = 1e-9


def free_start(
    project: Project,
    track_id: str,
    length: float,
    at: float,
    ignore: Iterable[str] = (),
    limit: float = float("inf"),
) -> float | None:
    """The earliest start >= `at` where [start, start + length) covers no clip of the track.

    Clips in `ignore` do not count. Returns None when no such start is below `limit`.
    """
    skip = set(ignore)
    spans = sorted((c.start, c.end) for c in project.track(track_id).clips if c.id not in skip)
    start = max(0.0, at)
    for a, b in spans:
        if b <= start + EPS:
            continue
        if a >= start + length - EPS:
            break
        start = b
    return start if start < limit else None


def overlaps(project: Project, track_id: str) -> dict[str, tuple[tuple[float, float], ...]]:
    """Per clip of a track, the axis spans where another clip of the same track covers it."""
    clips = project.track(track_id).clips
    found: dict[str, list[tuple[float, float]]] = {}
    for i, a in enumerate(clips):
        for b in clips[i + 1 :]:
            lo, hi = max(a.start, b.start), min(a.end, b.end)
            if hi - lo > EPS:
                found.setdefault(a.id, []).append((lo, hi))
                found.setdefault(b.id, []).append((lo, hi))
    return {k: tuple(sorted(v)) for k, v in found.items()}


def into_gap(project: Project, clip_ids: list[str], at: float) -> Project:
    """Move new clips (placed from `at` on) later together, to where none covers an older clip.

    Used after an import: the new material keeps its own layout and lands in the first gap on
    each of its tracks that holds all of it.
    """
    new = set(clip_ids)
    if not new:
        return project
    placed = [project.find_clip(i) for i in clip_ids]
    first = min(c.start for _, c in placed)
    shift = 0.0
    for track in {t.id for t, _ in placed}:
        mine = [c for t, c in placed if t.id == track]
        span = max(c.end for c in mine) - first
        start = free_start(project, track, span, first + shift, ignore=new)
        shift = max(shift, (start if start is not None else first) - first)
    if shift <= EPS:
        return project
    for clip_id in clip_ids:
        _, clip = project.find_clip(clip_id)
        project = edits.move_clip(project, clip_id, clip.start + shift)
    return project
