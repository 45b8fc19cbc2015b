"""Driving the timeline like a person: mouse on the viewport at a clip's scene position."""

from __future__ import annotations

from PySide6.QtCore import QPoint, QPointF, Qt
from PySide6.QtTest import QTest

NO = Qt.KeyboardModifier.NoModifier


def view_point(win, scene_point: QPointF) -> QPoint:
    """Viewport pixel of a scene position."""
    return win.view.mapFromScene(scene_point)


def clip_point(win, clip_id: str, fx: float = 0.5, fy: float = 0.6) -> QPoint:
    """A point inside a clip at fractions of its width and height."""
    rect = win.view.clip_scene_rect(clip_id)
    return view_point(
        win, QPointF(rect.left() + fx * rect.width(), rect.top() + fy * rect.height())
    )


def drag(win, start: QPoint, end: QPoint, modifiers=NO, steps: int = 5) -> None:
    """Press, move in steps and release with the left button."""
    vp = win.view.viewport()
    QTest.mousePress(vp, Qt.MouseButton.LeftButton, modifiers, start)
    for i in range(1, steps + 1):
        p = start + (end - start) * (i / steps)
        QTest.mouseMove(vp, p)
    QTest.mouseRelease(vp, Qt.MouseButton.LeftButton, modifiers, end)


def click(win, at: QPoint, modifiers=NO) -> None:
    QTest.mouseClick(win.view.viewport(), Qt.MouseButton.LeftButton, modifiers, at)
