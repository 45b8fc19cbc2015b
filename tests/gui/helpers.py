"""Driving the timeline like a person: mouse on the viewport at a clip's scene position."""

from __future__ import annotations

import numpy as np
from PySide6.QtCore import QEvent, QMimeData, QPoint, QPointF, Qt
from PySide6.QtGui import QDragEnterEvent, QDragMoveEvent, QDropEvent, QImage
from PySide6.QtTest import QTest
from PySide6.QtWidgets import QApplication

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


def painted_and_fresh(win) -> tuple[QImage, QImage]:
    """The lanes as painted so far (offscreen: the window's backing store) and as a fresh paint
    of them draws them."""
    viewport = win.view.viewport()
    corner = viewport.mapTo(win, QPoint(0, 0))
    screen = QApplication.primaryScreen()
    painted = screen.grabWindow(
        win.winId(), corner.x(), corner.y(), viewport.width(), viewport.height()
    )
    return painted.toImage(), viewport.grab().toImage()


def pixel_array(image: QImage) -> np.ndarray:
    """An image's pixels as a (height, width, 4) array of RGB32 bytes."""
    rgb = image.convertToFormat(QImage.Format.Format_RGB32)
    return np.frombuffer(rgb.constBits(), np.uint8).reshape(rgb.height(), rgb.width(), 4).copy()


def click(win, at: QPoint, modifiers=NO) -> None:
    QTest.mouseClick(win.view.viewport(), Qt.MouseButton.LeftButton, modifiers, at)


def send_drop(win, mime: QMimeData, at: QPoint) -> None:
    """What Qt delivers to the lanes while something is dragged over them and released."""
    vp = win.view.viewport()
    copy = Qt.DropAction.CopyAction
    nobutton = Qt.MouseButton.NoButton
    QApplication.sendEvent(vp, QDragEnterEvent(at, copy, mime, nobutton, NO))
    QApplication.sendEvent(vp, QDragMoveEvent(at, copy, mime, nobutton, NO))
    QApplication.sendEvent(vp, QDropEvent(QPointF(at), copy, mime, nobutton, NO, QEvent.Type.Drop))


def choose(qtbot, box, text: str) -> None:
    """Open a combo box with the mouse and pick `text` by keys, as a person does."""
    qtbot.mouseClick(box, Qt.MouseButton.LeftButton)
    qtbot.waitUntil(lambda: box.view().isVisible(), timeout=5_000)
    while box.view().currentIndex().data() != text:
        qtbot.keyClick(box.view(), Qt.Key.Key_Down)
    qtbot.keyClick(box.view(), Qt.Key.Key_Return)


def shown_window(qtbot, project, width: int = 1300, height: int = 800):
    """The main window on `project`, shown at this size, discarding unsaved changes on close."""
    from PySide6.QtWidgets import QMessageBox

    from timeline.gui.main_window import MainWindow

    win = MainWindow(project)
    win.ask_unsaved = lambda: QMessageBox.StandardButton.Discard
    qtbot.addWidget(win)
    win.resize(width, height)
    win.show()
    qtbot.waitExposed(win)
    return win
