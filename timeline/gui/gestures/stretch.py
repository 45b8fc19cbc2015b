"""Shift-drag a clip's edge to stretch it in time (the paper's frequency change)."""

from __future__ import annotations

from PySide6.QtCore import QPointF

from timeline import edits
from timeline.model import Project

from ..geometry import axis_text
from .base import Gesture

MIN_LENGTH_PX = 4.0


class StretchGesture(Gesture):
    """Stretch (squeeze) a clip so the dragged edge follows the mouse; the other edge stays."""

    label = "stretch clip"

    def __init__(self, view, press: QPointF, clip_id: str, side: str) -> None:
        super().__init__(view, press)
        self.clip_id, self.side = clip_id, side
        _, self.clip = self.base.find_clip(clip_id)

    def moved(self, pos: QPointF) -> None:
        g = self.view.lane_geometry
        du = g.u(pos.x() - self.press.x())
        clip = self.clip
        smallest = g.u(MIN_LENGTH_PX)
        if self.side == "right":
            end = self.view.snap(clip.end + du, [self.clip_id])
            length = max(smallest, end - clip.start)
            self.apply(_stretch_to, self.clip_id, clip.start, length / clip.duration)
        else:
            start = self.view.snap(clip.start + du, [self.clip_id])
            length = max(smallest, clip.end - start)
            self.apply(_stretch_to, self.clip_id, clip.end - length, length / clip.duration)

    def readout(self, project: Project) -> str:
        _, clip = project.find_clip(self.clip_id)
        length = axis_text(clip.duration, project.axis)
        return f"stretch x{clip.stretch:.3f} ({clip.stretch_mode}), length {length}"


def _stretch_to(project: Project, clip_id: str, start: float, factor: float) -> Project:
    project = edits.stretch_clip(project, clip_id, factor)
    return edits.move_clip(project, clip_id, start)
