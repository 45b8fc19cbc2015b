"""What every timeline gesture has: the view it works in, its start state and its merge key."""

from __future__ import annotations

from typing import TYPE_CHECKING

from PySide6.QtCore import QPointF

from timeline.errors import HapticTimelineError
from timeline.model import Project

if TYPE_CHECKING:
    from ..timeline_view import TimelineView


class Gesture:
    """A press-move-release interaction; subclasses override `moved` (and maybe `released`)."""

    label = "edit"

    def __init__(self, view: TimelineView, press: QPointF) -> None:
        self.view = view
        self.doc = view.doc
        self.base = view.doc.project
        self.press = press
        self.merge_key = object()
        self.dragged = False

    def move(self, pos: QPointF) -> None:
        """Follow the mouse (scene coordinates)."""
        if not self.dragged and (pos - self.press).manhattanLength() < 3:
            return
        self.dragged = True
        self.moved(pos)
        self.view.snap_line.commit()  # a move that applied no edit
        self.show_readout(pos)

    def show_readout(self, pos: QPointF) -> None:
        """Show the gesture's numbers beside the mouse while it drags."""
        try:
            text = self.readout(self.doc.project)
        except HapticTimelineError:
            return
        if text:
            self.view.show_readout(text, pos)

    def readout(self, project: Project) -> str:
        """What the drag has set, as numbers with units (empty: nothing to show)."""
        return ""

    def moved(self, pos: QPointF) -> None:
        """Apply the edit for the current mouse position."""

    def release(self, pos: QPointF) -> None:
        """Finish the gesture."""
        self.move(pos)

    def apply(self, edit, *args, **kwargs) -> object:
        """Apply an edit to the starting state, merged into this drag's single undo step.

        The snap line goes where the move's snaps placed it first: its strip and the edited
        clips are then repainted in one pass."""
        self.view.snap_line.commit()
        return self.doc.apply(
            self.label, edit, *args, base=self.base, merge_key=self.merge_key, **kwargs
        )
