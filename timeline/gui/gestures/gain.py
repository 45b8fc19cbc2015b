"""Drag a clip's top edge up or down to set its gain (dB-even: half a lane down halves it)."""

from __future__ import annotations

from PySide6.QtCore import QPointF

from timeline import edits
from timeline.model import Project

from ..geometry import gain_text
from .base import Gesture


class GainGesture(Gesture):
    """The clip's gain follows the pointer: up by half a lane doubles it, down halves it."""

    label = "clip gain"

    def __init__(self, view, press: QPointF, clip_id: str) -> None:
        super().__init__(view, press)
        self.clip_id = clip_id
        _, self.clip = self.base.find_clip(clip_id)
        self.half = max(8.0, view.lane_geometry.lane_height / 2 - 8)

    def moved(self, pos: QPointF) -> None:
        factor = 2.0 ** (-(pos.y() - self.press.y()) / self.half)
        self.apply(edits.set_clip_gain, self.clip_id, self.clip.gain * factor)

    def readout(self, project: Project) -> str:
        _, clip = project.find_clip(self.clip_id)
        return f"gain {gain_text(clip.gain)}"
