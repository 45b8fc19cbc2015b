"""Start the editor: a QApplication, the main window on a project, recovery offered."""

from __future__ import annotations

import sys
from pathlib import Path

from timeline.files import projectfile

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
    window.show()
    window.view.fit()
    window.offer_recovery()
    return app.exec()
