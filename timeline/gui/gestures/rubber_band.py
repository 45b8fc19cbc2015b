"""Drag on empty lanes to select the clips a rectangle touches (Ctrl adds to the selection)."""

from __future__ import annotations

from PySide6.QtCore import QPointF, QRectF, Qt
from PySide6.QtGui import QBrush, QColor, QPen

from .base import Gesture


class RubberBandGesture(Gesture):
    """Rectangle selection across tracks; a plain click on an empty lane clears the selection."""

    def __init__(self, view, press: QPointF, add: bool) -> None:
        super().__init__(view, press)
        self.keep = list(self.doc.selected_clips) if add else []
        self.rect = view.scene().addRect(
            QRectF(press, press),
            QPen(QColor("#3875d7"), 1, Qt.PenStyle.DashLine),
            QBrush(QColor(56, 117, 215, 40)),
        )
        self.rect.setZValue(10)
        if not add:
            self.doc.select_clips([])

    def moved(self, pos: QPointF) -> None:
        area = QRectF(self.press, pos).normalized()
        self.rect.setRect(area)
        hit = [
            item.clip.id
            for item in self.view.clip_items()
            if item.sceneBoundingRect().intersects(area)
        ]
        self.doc.select_clips(self.keep + hit)

    def release(self, pos: QPointF) -> None:
        super().release(pos)
        self.view.scene().removeItem(self.rect)
