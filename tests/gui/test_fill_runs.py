"""Runs of narrow clips (and the grid's columns) are filled as one image row: the same pixels
QPainter fills for the rectangles one by one."""

from __future__ import annotations

from PySide6.QtCore import QRectF, Qt
from PySide6.QtGui import QBrush, QColor, QImage, QPainter

from timeline.gui.clip_layer import fill_runs

SPANS = [(3.2, 9.7), (12.0, 14.5), (20.5, 31.49), (40.0, 41.0), (57.6, 88.3)]


def _painted(opacity: float, one_image: bool) -> QImage:
    image = QImage(100, 30, QImage.Format.Format_RGB32)
    image.fill(QColor("#d9d9d6"))
    painter = QPainter(image)
    painter.translate(4, -2)  # as the view's scroll offset does
    painter.setOpacity(opacity)
    colour = QColor(230, 126, 34, 130)
    if one_image:
        fill_runs(painter, SPANS, 5.0, 20.0, colour)
    else:
        painter.setPen(Qt.PenStyle.NoPen)
        painter.setBrush(QBrush(colour))
        painter.drawRects([QRectF(a, 5.0, b - a, 20.0) for a, b in SPANS])
    painter.end()
    return image


def test_the_runs_image_sets_the_pixels_the_rectangles_set(qapp) -> None:
    assert _painted(1.0, True) == _painted(1.0, False)
    assert _painted(1.0, True).pixelColor(4 + 21, 10) != QColor("#d9d9d6")  # 20.5 rounds up
    assert _painted(1.0, True).pixelColor(4 + 20, 10) == QColor("#d9d9d6")


def test_a_muted_lanes_opacity_blends_the_same_colour(qapp) -> None:
    faded, rects = _painted(0.35, True), _painted(0.35, False)
    assert faded.pixelColor(4 + 60, 10) == rects.pixelColor(4 + 60, 10)
    assert faded.pixelColor(4 + 60, 10) != _painted(1.0, True).pixelColor(4 + 60, 10)
