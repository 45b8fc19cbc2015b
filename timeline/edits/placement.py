"""Where a clip of some length fits on a track without covering another clip (Qt-free).

Duplicate, paste and import use it so that new material lands in a gap rather than on top of
what is there; when the track has no room before `limit`, the caller decides what to do.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import overload

import numpy as np

from timeline import edits
from timeline.model import Project

EPS = 1e-9


@overload
def free_start(
    project: Project, track_id: str, length: float, at: float, ignore: Iterable[str] = ()
) -> float: ...


@overload
def free_start(
    project: Project,
    track_id: str,
    length: float,
    at: float,
    ignore: Iterable[str] = (),
    limit: float = float("inf"),
) -> float | None: ...


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
    """Per clip of a track, the axis span where other clips of the track cover it (O(n log n)).

    The span runs from where the first other clip reaches into it to where the last one leaves
    it (gaps between several covering clips are not split out: it is what the lane hatches).
    """
    track_clips = project.track(track_id).clips
    if len(track_clips) < 2:
        return {}
    starts = np.array([c.start for c in track_clips], dtype=np.float64)
    ends = np.array([c.end for c in track_clips], dtype=np.float64)
    order = np.lexsort((ends, starts))  # by start, then end; stable as sorted() is
    lo, hi = covered_spans(starts[order], ends[order])
    found: dict[str, tuple[tuple[float, float], ...]] = {}
    for i in np.flatnonzero(hi - lo > EPS).tolist():
        found[track_clips[order[i]].id] = ((float(lo[i]), float(hi[i])),)
    return found


def covered_spans(starts: np.ndarray, ends: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """`overlaps` on clips already in (start, end) order, as arrays: each clip's covered span
    runs from lo to hi, where hi - lo > EPS."""
    reach = np.r_[-np.inf, np.maximum.accumulate(ends)[:-1]]  # max end of the clips before
    later = np.r_[np.maximum.accumulate(ends[::-1])[::-1][1:], -np.inf]  # of the clips after
    following = np.r_[starts[1:], np.inf]  # the next clip's start
    lo = np.where(reach > starts + EPS, starts, np.inf)  # earlier clips cover its start
    hi = np.where(reach > starts + EPS, np.minimum(ends, reach), -np.inf)
    inside = following < ends - EPS  # later clips start inside it
    lo = np.where(inside, np.minimum(lo, following), lo)
    hi = np.where(inside, np.maximum(hi, np.minimum(ends, later)), hi)
    return lo, hi


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
    return edits.shift_clips(project, clip_ids, shift)
