"""Runs of narrow clips (and the grid's columns) are filled as one image row: the same pixels
QPainter fills for the rectangles one by one."""

from __future__ import annotations

import numpy as np
from PySide6.QtCore import QRectF, Qt
from PySide6.QtGui import QBrush, QColor, QImage, QPainter

from timeline.gui.clip_layer import fill_column, fill_runs, premultiplied

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


ROWS = {3: QColor("#f4f4f2"), 4: QColor(0, 0, 0, 22), 9: QColor(0, 0, 0, 45), 17: QColor("#c8c8c4")}


def _rows(opacity: float, one_image: bool) -> QImage:
    image = QImage(60, 30, QImage.Format.Format_RGB32)
    image.fill(QColor("#d9d9d6"))
    painter = QPainter(image)
    painter.translate(4, -2)  # as the view's scroll offset does
    painter.setOpacity(opacity)
    if one_image:
        pixels = np.zeros(20, dtype=np.uint32)
        for row, colour in ROWS.items():
            pixels[row - 2] = premultiplied(colour, opacity)
        fill_column(painter, pixels, 2, 6.0, 41.0)
    else:
        for row, colour in ROWS.items():
            painter.fillRect(QRectF(6.0, row, 35.0, 1), colour)
    painter.end()
    return image


def test_a_column_of_pixels_sets_the_pixels_the_row_fills_set(qapp) -> None:
    """The lanes' bands and edges and the scale's level lines: one image stretched across."""
    for opacity in (1.0, 0.35):
        assert _rows(opacity, True) == _rows(opacity, False)
    assert _rows(1.0, True).pixelColor(4 + 6, 3 - 2) == QColor("#f4f4f2")
    assert _rows(1.0, True).pixelColor(4 + 41, 3 - 2) == QColor("#d9d9d6")  # right of the rows
