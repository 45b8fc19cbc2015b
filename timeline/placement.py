"""Where a clip of some length fits on a track without covering another clip (Qt-free).

Duplicate, paste and import use it so that new material lands in a gap rather than on top of
what is there; when the track has no room before `limit`, the caller decides what to do.
"""

from __future__ import annotations

from collections.abc import Iterable

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
