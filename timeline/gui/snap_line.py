"""The line drawn across the lanes where a drag has snapped (hidden when it has not)."""

from __future__ import annotations

from PySide6.QtCore import QLineF, Qt
from PySide6.QtGui import QColor, QPen
from PySide6.QtWidgets import QGraphicsLineItem, QGraphicsScene

from .geometry import Geometry


class SnapLine:
    """A dashed vertical line at the snapped position, shown only while a drag is snapped."""

    def __init__(self, scene: QGraphicsScene, geometry: Geometry) -> None:
        self.geometry = geometry
        self.line = QGraphicsLineItem()
        self.line.setPen(QPen(QColor("#e07000"), 1, Qt.PenStyle.DashLine))
        self.line.setZValue(21)
        self.line.hide()
        scene.addItem(self.line)
        self.at: float | None = None

    def show_at(self, u: float | None) -> None:
        """Draw the line at axis position u (None hides it)."""
        self.at = u
        if u is None:
            self.line.hide()
            return
        x = self.geometry.x(u)
        self.line.setLine(QLineF(x, 0, x, self.line.scene().sceneRect().height()))
        self.line.show()
