"""Drag a clip's edge to trim it; the content stays where it is."""

from __future__ import annotations

from PySide6.QtCore import QPointF

from timeline import edits
from timeline.model import Project

from ..geometry import axis_text
from ..ripple import trim_end_rippled
from .base import Gesture


class TrimGesture(Gesture):
    """Move the left or right edge of a clip."""

    label = "trim clip"

    def __init__(self, view, press: QPointF, clip_id: str, side: str) -> None:
        super().__init__(view, press)
        self.clip_id, self.side = clip_id, side
        _, self.clip = self.base.find_clip(clip_id)

    def moved(self, pos: QPointF) -> None:
        du = self.view.lane_geometry.u(pos.x() - self.press.x())
        if self.side == "left":
            start = self.view.snap(self.clip.start + du, [self.clip_id])
            self.apply(edits.trim_clip, self.clip_id, start=start)
        else:
            end = self.view.snap(self.clip.end + du, [self.clip_id])
            if self.view.ripple:  # the later clips of the track follow the end
                self.apply(trim_end_rippled, self.clip_id, end)
            else:
                self.apply(edits.trim_clip, self.clip_id, end=end)

    def readout(self, project: Project) -> str:
        _, clip = project.find_clip(self.clip_id)
        edge = clip.start if self.side == "left" else clip.end
        name = "start" if self.side == "left" else "end"
        axis = project.axis
        return f"{name} {axis_text(edge, axis)}, length {axis_text(clip.duration, axis)}"
