"""Shift-drag a clip vertically to scale its amplitude about its mirror line (paper, Fig. 9)."""

from __future__ import annotations

from PySide6.QtCore import QPointF

from timeline import edits
from timeline.model import Project

from ..geometry import gain_text
from .base import Gesture


class AmplitudeGesture(Gesture):
    """Dragging up by half a lane doubles the amplitude about the pivot; down halves it."""

    label = "scale amplitude"

    def __init__(self, view, press: QPointF, clip_id: str) -> None:
        super().__init__(view, press)
        self.clip_id = clip_id
        self.half = max(8.0, view.lane_geometry.lane_height / 2 - 8)

    def moved(self, pos: QPointF) -> None:
        dy = pos.y() - self.press.y()
        factor = 2.0 ** (-dy / self.half)
        self.apply(edits.scale_clip, self.clip_id, factor)

    def readout(self, project: Project) -> str:
        _, clip = project.find_clip(self.clip_id)
        return f"amplitude {gain_text(clip.scale)} about the mirror line {clip.pivot:.3g}"
