"""The context menu of a fade handle: the fade's shape, the current one checked."""

from __future__ import annotations

from PySide6.QtGui import QActionGroup
from PySide6.QtWidgets import QMenu, QWidget

from timeline import edits
from timeline.model import FADE_SHAPES

from .document import Document

SHAPE_TIPS = {
    "linear": "straight line: the gain rises evenly",
    "equal-power": "quarter sine: keeps the energy even across a crossfade",
    "exponential": "slow start, fast finish: sounds even to the skin on a log scale",
    "s-curve": "smooth at both ends",
}


def fade_shape_menu(doc: Document, clip_id: str, which: str, parent: QWidget) -> QMenu:
    """A menu that sets the shape of one fade (in or out) of one clip, as one undo step."""
    _, clip = doc.project.find_clip(clip_id)
    fade = clip.fade_in if which == "in" else clip.fade_out
    menu = QMenu(f"Fade-{which} shape", parent)
    menu.setToolTipsVisible(True)
    group = QActionGroup(menu)
    for shape in FADE_SHAPES:
        action = menu.addAction(shape)
        action.setCheckable(True)
        action.setChecked(shape == fade.shape)
        action.setToolTip(SHAPE_TIPS.get(shape, ""))
        group.addAction(action)
        action.triggered.connect(
            lambda _=False, s=shape: doc.apply(
                f"fade-{which} shape", edits.set_fade, clip_id, which, fade.length, s
            )
        )
    return menu
