"""Place a clip's horizontal mirror line at the mouse's level: Ctrl+Shift+click (or drag), the
clip menu's "Set mirror line here", or Alt+click where the window manager leaves Alt alone."""

from __future__ import annotations

from PySide6.QtCore import QPointF, Qt

from timeline import edits
from timeline.model import Project

from .base import Gesture

CTRL_SHIFT = Qt.KeyboardModifier.ControlModifier | Qt.KeyboardModifier.ShiftModifier


def places_mirror_line(mods: Qt.KeyboardModifier) -> bool:
    """Whether a press with these keys held places the mirror line: Ctrl+Shift (most Linux
    window managers take Alt+drag to move windows), or Alt."""
    return (mods & CTRL_SHIFT) == CTRL_SHIFT or bool(mods & Qt.KeyboardModifier.AltModifier)


class PivotGesture(Gesture):
    """Place the clip's mirror line (what amplitude drags and inversion turn about)."""

    label = "place mirror line"

    def __init__(self, view, press: QPointF, clip_id: str) -> None:
        super().__init__(view, press)
        self.clip_id = clip_id
        self.moved(press)

    def move(self, pos: QPointF) -> None:
        self.moved(pos)

    def moved(self, pos: QPointF) -> None:
        item = self.view.clip_item(self.clip_id)
        value = round(item.y_value(item.mapFromScene(pos).y()), 3)
        self.apply(edits.set_pivot, self.clip_id, value)

    def readout(self, project: Project) -> str:
        _, clip = project.find_clip(self.clip_id)
        return f"mirror line at {clip.pivot:.3g} of full scale"
