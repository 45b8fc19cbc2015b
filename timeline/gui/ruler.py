"""The ruler above the lanes: seconds, or degrees in position mode; click to place the cursor."""

from __future__ import annotations

import math

from PySide6.QtCore import QPointF, Qt, Signal
from PySide6.QtGui import QColor, QFont, QMouseEvent, QPainter, QPen
from PySide6.QtWidgets import QWidget

from .geometry import display_factor, display_unit, format_tick, nice_step
from .timeline_view import TimelineView

HEIGHT = 26


class Ruler(QWidget):
    """Tick marks and labels that follow the view's zoom and scroll."""

    clicked = Signal(float)  # axis position the playhead and cursor moved to

    def __init__(self, view: TimelineView) -> None:
        super().__init__()
        self.view = view
        self.setFixedHeight(HEIGHT)
        view.zoomed.connect(self.update)
        view.doc.changed.connect(self.update)

    def paintEvent(self, event) -> None:
        painter = QPainter(self)
        painter.fillRect(self.rect(), QColor("#fafaf8"))
        axis = self.view.doc.project.axis
        g = self.view.geometry
        factor = display_factor(axis)
        step = nice_step(g.px_per_unit / factor)
        left = self.view.horizontalScrollBar().value()
        first = math.floor(g.u(left) * factor / step)
        last = math.ceil(g.u(left + self.width()) * factor / step)
        font = QFont()
        font.setPointSizeF(8.0)
        painter.setFont(font)
        for i in range(first, last + 1):
            x = g.x(i * step / factor) - left
            painter.setPen(QPen(QColor("#555555"), 1))
            painter.drawLine(QPointF(x, HEIGHT - 9), QPointF(x, HEIGHT))
            painter.drawText(QPointF(x + 3, 12), format_tick(i * step, step) + display_unit(axis))
            for sub in range(1, 4):
                xs = x + g.x(step / factor) * sub / 4
                painter.setPen(QPen(QColor("#aaaaaa"), 1))
                painter.drawLine(QPointF(xs, HEIGHT - 4), QPointF(xs, HEIGHT))
        painter.setPen(QPen(QColor("#bbbbbb"), 1))
        painter.drawLine(0, HEIGHT - 1, self.width(), HEIGHT - 1)
        x = g.x(self.view.scene().playhead_u) - left
        painter.setPen(QPen(QColor("#d00000"), 2))
        painter.drawLine(QPointF(x, 0), QPointF(x, HEIGHT))

    def mousePressEvent(self, event: QMouseEvent) -> None:
        if event.button() == Qt.MouseButton.LeftButton:
            x = event.position().x() + self.view.horizontalScrollBar().value()
            u = max(0.0, self.view.geometry.u(x))
            self.view.scene().set_cursor(u)
            self.view.scene().set_playhead(u)
            self.update()
            self.clicked.emit(u)
