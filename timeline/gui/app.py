"""Start the editor: a QApplication, the main window on a project, recovery offered."""

from __future__ import annotations

import gc
import os
import sys
from pathlib import Path
from typing import TYPE_CHECKING

# Before numpy loads, as the command line does (cli.main.one_blas_thread): OpenBLAS's worker
# threads start spinning as it loads and cost the first paint about 60 ms of CPU.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

# Imported before PySide6, whose import hook would otherwise read the source of numpy's and the
# tiles' inner modules ("The editor at 20,000 clips" in docs/performance.md).
from timeline.files import projectfile  # noqa: E402

if TYPE_CHECKING:
    from PySide6.QtCore import QRect
    from PySide6.QtWidgets import QApplication, QWidget

    from .main_window import MainWindow

ORGANISATION = "haptic-timeline"  # QSettings (recent files) live under this name


def run(path: str | None = None) -> int:
    """Open the editor (on a project file, or a new project) and run until it closes."""
    app, _window = launch(path)
    return app.exec()


def launch(path: str | None = None) -> tuple[QApplication, MainWindow]:
    """The application and its window shown on a project (painted once the event loop runs).

    The first frame shows the lanes, the transport and the menu bar; the palette, the waveform
    editor, the inspector, the menus' actions, the findings overlay and the track headers below
    the screen's height are built right after it (MainWindow's `panels_after_paint`). Nothing
    on the way to the first paint loads scipy.signal or numba: the findings check starts after
    it (findings_overlay) and the sound analysis with the first sound converted.
    """
    collecting = gc.isenabled()
    gc.disable()  # until the first paint (see _after_first_paint)
    try:
        app, window = _shown(path)
    except BaseException:
        if collecting:
            gc.enable()
        raise
    _after_first_paint(window, collecting)
    return app, window


def _shown(path: str | None) -> tuple[QApplication, MainWindow]:
    """The project loaded and its window shown."""
    from PySide6.QtWidgets import QApplication

    from .main_window import MainWindow

    project = projectfile.load(path) if path and Path(path).exists() else None
    app = QApplication.instance() or QApplication(sys.argv[:1])
    assert isinstance(app, QApplication)
    app.setOrganizationName(ORGANISATION)
    app.setApplicationName("haptic-timeline")
    window = MainWindow(project, Path(path) if path else None, panels_after_paint=True)
    screen = QApplication.primaryScreen()
    if screen is not None:
        fit_to_screen(window, screen.availableGeometry(), keep_place=window.restored)
    window.show()
    window.view.fit()
    return app, window


def _after_first_paint(window: MainWindow, collecting: bool) -> None:
    """What waits for the window's first paint: a crashed session's autosave offered (the
    autosave folder read), and the cyclic garbage collector turned back on if it was.

    Launching allocates some hundred thousand objects (modules, Qt enums, the project), none
    of them garbage; the collector ran about 90 times over them before the first paint
    (25-45 ms of CPU). Reference counting frees everything as usual meanwhile.
    """
    from .first_paint import after_first_paint

    after_first_paint(window.view.viewport(), window.offer_recovery)
    if collecting:
        after_first_paint(window.view.viewport(), gc.enable)


def fit_to_screen(window: QWidget, available: QRect, keep_place: bool = False) -> None:
    """Shrink the window to the screen's free area (a 1280x800 laptop) and place it there;
    it never goes below its own minimum size. With `keep_place` (the size and place remembered
    from the last session), it moves only if it would not lie wholly inside that area."""
    size = window.size().boundedTo(available.size()).expandedTo(window.minimumSizeHint())
    window.resize(size)
    if not (keep_place and available.contains(window.geometry())):
        window.move(available.topLeft())
