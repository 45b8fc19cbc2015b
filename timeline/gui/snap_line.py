"""The line drawn across the lanes where a drag has snapped (hidden when it has not)."""

from __future__ import annotations

from PySide6.QtCore import QLineF, Qt
from PySide6.QtGui import QColor, QPen
from PySide6.QtWidgets import QGraphicsLineItem, QGraphicsScene

from .geometry import Geometry


class SnapLine:
    """A dashed vertical line at the snapped position, shown only while a drag is snapped.

    A drag may snap more than once per mouse move (a moved clip tries its start, then its end):
    each snap `place`s the line and the move `commit`s it once, so the full-height line is
    redrawn only when where it is shown changes, not hidden and shown again on every move.
    """

    def __init__(self, scene: QGraphicsScene, geometry: Geometry) -> None:
        self.geometry = geometry
        self.line = QGraphicsLineItem()
        self.line.setPen(QPen(QColor("#e07000"), 1, Qt.PenStyle.DashLine))
        self.line.setZValue(21)
        self.line.hide()
        scene.addItem(self.line)
        self.at: float | None = None  # where the line is shown (None: hidden)
        self.placed: float | None = None  # where the next commit shows it

    def place(self, u: float | None) -> None:
        """Where the line goes at the next `commit` (None hides it)."""
        self.placed = u

    def commit(self) -> None:
        """Show the line where it was last placed; nothing is redrawn when that is unchanged."""
        u = self.placed
        self.at = u
        if u is None:
            if self.line.isVisible():
                self.line.hide()
            return
        x = self.geometry.x(u)
        line = QLineF(x, 0, x, self.line.scene().sceneRect().height())
        if line != self.line.line():
            self.line.setLine(line)
        if not self.line.isVisible():
            self.line.show()

    def show_at(self, u: float | None) -> None:
        """Draw the line at axis position u now (None hides it)."""
        self.place(u)
        self.commit()
