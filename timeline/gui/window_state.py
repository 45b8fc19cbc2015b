"""What the window remembers between sessions (QSettings): its size and place, the splitters'
positions, the docks, and the hand (model, mode and its speed or torque)."""

from __future__ import annotations

import contextlib
from typing import TYPE_CHECKING

from PySide6.QtCore import QByteArray, QPoint, QSettings, QSize, Qt

if TYPE_CHECKING:
    from .main_window import MainWindow

SIZE, PLACE, MAXIMISED = "window/size", "window/place", "window/maximised"
DOCKS = "window/docks"
SPLITTERS = "window/splitters/"  # + the splitter's name
HAND = "hand/"  # + model, mode, value


def save(window: MainWindow) -> None:
    """Remember the window's layout and the hand."""
    settings = QSettings()
    normal = window.normalGeometry() if window.isMaximized() else window.geometry()
    settings.setValue(SIZE, normal.size())
    settings.setValue(PLACE, normal.topLeft())
    settings.setValue(MAXIMISED, window.isMaximized())
    settings.setValue(DOCKS, window.saveState())
    for name, splitter in window.splitters().items():
        settings.setValue(SPLITTERS + name, splitter.saveState())
    t = window.transport
    settings.setValue(HAND + "model", t.hand_model.currentText())
    settings.setValue(HAND + "mode", t.hand.currentText())
    settings.setValue(HAND + "value", t.hand_value.value())
    settings.sync()


def restore(window: MainWindow) -> bool:
    """Put back what `save` remembered; returns whether the window's geometry was restored."""
    settings = QSettings()
    t = window.transport
    for key, box in (("model", t.hand_model), ("mode", t.hand)):
        text = settings.value(HAND + key, "", type=str)
        if isinstance(text, str) and text and box.findText(text) >= 0:
            box.setCurrentText(text)
    value = settings.value(HAND + "value", None)
    if value is not None and t.hand.currentText() in ("turn", "push"):
        with contextlib.suppress(TypeError, ValueError):
            t.hand_value.setValue(float(value))  # type: ignore[arg-type]
    for name, splitter in window.splitters().items():
        state = settings.value(SPLITTERS + name)
        if isinstance(state, QByteArray):
            splitter.restoreState(state)
    size, place = settings.value(SIZE), settings.value(PLACE)
    restored = isinstance(size, QSize) and isinstance(place, QPoint)
    if restored:  # app.fit_to_screen keeps it on the screen it opens on
        window.resize(size.expandedTo(window.minimumSizeHint()))
        window.move(place)
        if settings.value(MAXIMISED, False, type=bool):
            window.setWindowState(window.windowState() | Qt.WindowState.WindowMaximized)
    docks = settings.value(DOCKS)
    if isinstance(docks, QByteArray):
        window.restoreState(docks)
    return restored
