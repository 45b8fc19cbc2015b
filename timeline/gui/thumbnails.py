"""Small pictures of tile shapes for the palette."""

from __future__ import annotations

import numpy as np
from PySide6.QtCore import QPointF, Qt
from PySide6.QtGui import QColor, QPainter, QPen, QPixmap, QPolygonF

from timeline.tiles import Tile

from .clip_shape import tile_pyramid

SIZE = (96, 44)


def thumbnail(tile: Tile, rate: float, colour: str = "#3a6ea5") -> QPixmap:
    """A min/max picture of a tile's whole shape, scaled to its own peak."""
    w, h = SIZE
    pixmap = QPixmap(w, h)
    pixmap.fill(QColor("#ffffff"))
    pyramid, data_rate = tile_pyramid(tile, rate)
    lo, hi = pyramid.columns(0, len(pyramid), w - 4)
    peak = float(max(np.abs(lo).max(), np.abs(hi).max(), 1e-12))
    mid = h / 2

    def y(v: float) -> float:
        return mid - v / peak * (mid - 3)

    xs = 2 + np.arange(len(lo)) + 0.5
    top = [QPointF(x, y(v)) for x, v in zip(xs, hi, strict=True)]
    bottom = [QPointF(x, y(v)) for x, v in zip(xs[::-1], lo[::-1], strict=True)]
    painter = QPainter(pixmap)
    painter.setRenderHint(QPainter.RenderHint.Antialiasing)
    painter.setPen(QPen(QColor("#dddddd"), 1))
    painter.drawLine(QPointF(0, mid), QPointF(w, mid))
    painter.setPen(QPen(QColor(colour), 1))
    painter.setBrush(QColor(colour))
    painter.drawPolygon(QPolygonF(top + bottom))
    painter.setPen(QPen(QColor("#bbbbbb"), 1))
    painter.setBrush(Qt.BrushStyle.NoBrush)
    painter.drawRect(0, 0, w - 1, h - 1)
    painter.end()
    return pixmap
