"""A live scope of the knob's angle (theta) and torque (tau) from the playing device."""

from __future__ import annotations

import numpy as np
from PySide6.QtCore import QPointF
from PySide6.QtGui import QColor, QFont, QPainter, QPen, QPolygonF
from PySide6.QtWidgets import QWidget

HISTORY = 4000  # columns kept (decimated samples)


class Scope(QWidget):
    """Two traces scrolling right to left: theta (degrees) and tau (mNm)."""

    def __init__(self) -> None:
        super().__init__()
        self.setMinimumSize(260, 90)
        self.theta = np.zeros(0)
        self.tau = np.zeros(0)
        self.waiting = False  # playing, and the device has not reported yet

    def clear(self) -> None:
        self.theta, self.tau = np.zeros(0), np.zeros(0)
        self.update()

    def add(self, angle: np.ndarray, torque: np.ndarray) -> None:
        """Append telemetry (rad, N*m), decimated to one point per 10 samples."""
        self.theta = np.concatenate([self.theta, np.degrees(angle[::10])])[-HISTORY:]
        self.tau = np.concatenate([self.tau, 1e3 * np.asarray(torque)[::10]])[-HISTORY:]
        self.update()

    def paintEvent(self, event) -> None:
        painter = QPainter(self)
        painter.fillRect(self.rect(), QColor("#101418"))
        w, h = self.width(), self.height()
        half = h / 2
        font = QFont()
        font.setPointSizeF(8.0)
        painter.setFont(font)
        for row, (values, colour, unit, name) in enumerate(
            ((self.theta, "#5fd3f3", "°", "θ"), (self.tau, "#f7b32b", " mNm", "τ"))
        ):
            top = row * half
            painter.setPen(QPen(QColor("#2a3138"), 1))
            painter.drawLine(QPointF(0, top + half / 2), QPointF(w, top + half / 2))
            peak = float(np.abs(values).max()) if values.size else 0.0
            scale = max(peak, 1e-9)
            if values.size > 1:
                xs = np.linspace(0, w, values.size)
                ys = top + half / 2 - values / scale * (half / 2 - 4)
                painter.setPen(QPen(QColor(colour), 1))
                painter.drawPolyline(
                    QPolygonF([QPointF(x, y) for x, y in zip(xs, ys, strict=True)])
                )
            painter.setPen(QColor(colour))
            last = values[-1] if values.size else 0.0
            painter.drawText(QPointF(6, top + 13), f"{name} {last:+.2f}{unit}  (±{peak:.2f})")
        if not self.tau.size:
            painter.setPen(QColor("#8a949e"))
            hint = (
                "Starting the device…"
                if self.waiting
                else "Press Space to play on the device and feel it"
            )
            painter.drawText(self.rect(), 0x84, hint)
