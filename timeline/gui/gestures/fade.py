"""Drag a fade handle at a clip's top corner to set the fade's length."""

from __future__ import annotations

from PySide6.QtCore import QPointF

from timeline import edits
from timeline.model import Project

from ..geometry import axis_text
from .base import Gesture


class FadeGesture(Gesture):
    """Set the fade-in or fade-out length from the handle's position (keeps the shape)."""

    label = "fade"

    def __init__(self, view, press: QPointF, clip_id: str, which: str) -> None:
        super().__init__(view, press)
        self.clip_id, self.which = clip_id, which
        _, self.clip = self.base.find_clip(clip_id)
        self.label = f"fade {which}"

    def moved(self, pos: QPointF) -> None:
        clip = self.clip
        u = self.view.lane_geometry.u(pos.x())
        length = u - clip.start if self.which == "in" else clip.end - u
        length = min(max(0.0, length), clip.duration)
        fade = clip.fade_in if self.which == "in" else clip.fade_out
        self.apply(edits.set_fade, self.clip_id, self.which, length, fade.shape)

    def readout(self, project: Project) -> str:
        _, clip = project.find_clip(self.clip_id)
        fade = clip.fade_in if self.which == "in" else clip.fade_out
        return f"fade {self.which} {axis_text(fade.length, project.axis)} ({fade.shape})"
