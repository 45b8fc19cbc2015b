"""Drag a clip's body along its track and across tracks (the new track gives it meaning); in
ripple mode the later clips of its track move along by as much."""

from __future__ import annotations

from PySide6.QtCore import QPointF

from timeline import edits
from timeline.edits.vibration import with_emphasis
from timeline.model import Project

from ..geometry import axis_text
from ..ripple import followers
from .base import Gesture


class MoveGesture(Gesture):
    """Move the pressed clip, and the other selected clips (and a vibration design's emphasis
    clips, timeline.edits.vibration.emphasis_of) with it in time; with ripple edit on, the
    clips after them on their tracks follow by the same time (they stay on their tracks)."""

    label = "move clip"

    def __init__(self, view, press: QPointF, clip_id: str) -> None:
        super().__init__(view, press)
        self.clip_id = clip_id
        carried = with_emphasis(self.base, [clip_id, *self.doc.selected_clips])
        self.others = [c for c in carried if c != clip_id]
        if view.ripple:
            self.others += followers(self.base, carried)
        track, self.clip = self.base.find_clip(clip_id)
        self.track_id = track.id

    def moved(self, pos: QPointF) -> None:
        g = self.view.lane_geometry
        du = g.u(pos.x() - self.press.x())
        moving = [self.clip_id, *self.others]
        raw = self.clip.start + du
        start = self.view.snap(raw, moving)
        if start == raw:
            start = self.view.snap(raw + self.clip.duration, moving) - self.clip.duration
        start = max(0.0, start) if self.base.axis == "time" else start
        target = self.view.track_at(pos.y())
        track_id = target.id if target is not None else self.track_id
        shift = start - self.clip.start
        self.apply(_move_all, self.clip_id, start, track_id, self.others, shift)

    def readout(self, project: Project) -> str:
        track, clip = project.find_clip(self.clip_id)
        return f"start {axis_text(clip.start, project.axis)} on {track.name}"


def _move_all(
    project: Project, clip_id: str, start: float, track_id: str, others: list[str], shift: float
) -> Project:
    project = edits.move_clip(project, clip_id, start, track_id)
    return edits.shift_clips(project, others, shift)
