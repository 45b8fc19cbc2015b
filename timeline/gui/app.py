"""Start the editor: a QApplication, the main window on a project, recovery offered."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import TYPE_CHECKING

from timeline.files import projectfile

if TYPE_CHECKING:
    from PySide6.QtCore import QRect
    from PySide6.QtWidgets import QWidget

ORGANISATION = "haptic-timeline"  # QSettings (recent files) live under this name


def run(path: str | None = None) -> int:
    """Open the editor (on a project file, or a new project) and run until it closes."""
    from PySide6.QtWidgets import QApplication

    from .main_window import MainWindow

    project = projectfile.load(path) if path and Path(path).exists() else None
    app = QApplication.instance() or QApplication(sys.argv[:1])
    app.setOrganizationName(ORGANISATION)
    app.setApplicationName("haptic-timeline")
    window = MainWindow(project, Path(path) if path else None)
    screen = QApplication.primaryScreen()
    if screen is not None:
        fit_to_screen(window, screen.availableGeometry(), keep_place=window.restored)
    window.show()
    window.view.fit()
    window.offer_recovery()
    return app.exec()


def fit_to_screen(window: QWidget, available: QRect, keep_place: bool = False) -> None:
    """Shrink the window to the screen's free area (a 1280x800 laptop) and place it there;
    it never goes below its own minimum size. With `keep_place` (the size and place remembered
    from the last session), it moves only if it would not lie wholly inside that area."""
    size = window.size().boundedTo(available.size()).expandedTo(window.minimumSizeHint())
    window.resize(size)
    if not (keep_place and available.contains(window.geometry())):
        window.move(available.topLeft())
