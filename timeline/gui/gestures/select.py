"""Shift+click on a clip extends the selection: every clip between the first selected clip and
the clicked one, in time and across the tracks between them (Qt-free)."""

from __future__ import annotations

from timeline.model import Project


def extended(project: Project, selected: list[str], clip_id: str) -> list[str]:
    """The selection extended from its first clip (the anchor) to `clip_id`."""
    if not selected:
        return [clip_id]
    lanes = {c.id: i for i, t in enumerate(project.tracks) for c in t.clips}
    anchor = project.find_clip(selected[0])[1]
    clicked = project.find_clip(clip_id)[1]
    t0, t1 = min(anchor.start, clicked.start), max(anchor.end, clicked.end)
    l0, l1 = sorted((lanes[anchor.id], lanes[clip_id]))
    inside = [
        c.id
        for lane in range(l0, l1 + 1)
        for c in project.tracks[lane].clips
        if c.start < t1 and c.end > t0
    ]
    return list(dict.fromkeys([*selected, *inside]))
