"""A live scope of the knob's angle (theta) and torque (tau) from the playing device.

A paint holds the interpreter lock, which the playing thread needs for every block, so it stays
small: each trace is cut down to one (min, max) pair per pixel column with numpy and written
straight into a reused QPolygonF's memory (no Python object per point), and the scope repaints
only when new telemetry arrived.
"""

from __future__ import annotations

from typing import Any, cast

import numpy as np
import shiboken6
from PySide6.QtCore import QPointF
from PySide6.QtGui import QColor, QFont, QPainter, QPen, QPolygonF
from PySide6.QtWidgets import QWidget

HISTORY = 4000  # columns kept (decimated samples)


def column_extremes(values: np.ndarray, columns: int) -> tuple[np.ndarray, np.ndarray]:
    """The (min, max) of the values falling in each of `columns` pixel columns.

    Value j of n falls in column j * columns // n (its x on the widget); needs n >= columns, so
    that no column is empty.
    """
    n = values.size
    starts = -(-(np.arange(columns) * n) // columns)  # the first j of each column: ceil(i n / c)
    return np.minimum.reduceat(values, starts), np.maximum.reduceat(values, starts)


def trace_points(values: np.ndarray, width: int) -> np.ndarray:
    """(x, value) rows to draw `values` across `width` pixels as one polyline.

    Up to one value per pixel the values are drawn as they are; beyond, each pixel column gets
    its min and max (in alternating order, so the line zig-zags inside each column's range).
    """
    n = values.size
    if n <= width:
        xs = np.linspace(0.0, float(width), n)
        return np.column_stack([xs, values])
    lo, hi = column_extremes(values, width)
    flip = np.arange(width) % 2 == 1
    first, second = np.where(flip, hi, lo), np.where(flip, lo, hi)
    points = np.empty((2 * width, 2))
    points[:, 0] = np.repeat(np.arange(width, dtype=np.float64) + 0.5, 2)
    points[0::2, 1], points[1::2, 1] = first, second
    return points


class _Polyline:
    """A QPolygonF reused from paint to paint, filled from numpy through its own memory."""

    def __init__(self) -> None:
        self.polygon = QPolygonF()
        self._memory = np.zeros((0, 2))

    def filled(self, points: np.ndarray) -> QPolygonF:
        if len(points) != len(self._memory):
            self.polygon = QPolygonF()
            self.polygon.resize(len(points))
            if len(points):  # the polygon's QPointF array: x, y as consecutive doubles
                size = points.size * 8
                memory = shiboken6.VoidPtr(self.polygon.data(), size, True)  # pyright: ignore[reportCallIssue]
                self._memory = np.frombuffer(cast(Any, memory), np.float64).reshape(-1, 2)
            else:
                self._memory = np.zeros((0, 2))
        self._memory[:] = points
        return self.polygon


class Scope(QWidget):
    """Two traces scrolling right to left: theta (degrees) and tau (mNm)."""

    def __init__(self) -> None:
        super().__init__()
        self.setMinimumSize(260, 90)
        self.theta = np.zeros(0)
        self.tau = np.zeros(0)
        self.waiting = False  # playing, and the device has not reported yet
        self._lines = (_Polyline(), _Polyline())

    def clear(self) -> None:
        self.theta, self.tau = np.zeros(0), np.zeros(0)
        self.update()

    def add(self, angle: np.ndarray, torque: np.ndarray) -> None:
        """Append telemetry (rad, N*m), decimated to one point per 10 samples; repaint if any."""
        if not len(angle):
            return
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
                points = trace_points(values, max(1, w))
                points[:, 1] = top + half / 2 - points[:, 1] / scale * (half / 2 - 4)
                painter.setPen(QPen(QColor(colour), 1))
                painter.drawPolyline(self._lines[row].filled(points))
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
