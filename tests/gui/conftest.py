"""GUI tests run offscreen, with the user data directory in a temporary folder."""

from __future__ import annotations

import os

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

import pytest  # noqa: E402

from timeline import edits  # noqa: E402
from timeline.model import Project  # noqa: E402
from timeline.tiles import generator  # noqa: E402


@pytest.fixture(autouse=True)
def data_home(tmp_path, monkeypatch):
    """Autosaves go to a temporary folder."""
    monkeypatch.setenv("XDG_DATA_HOME", str(tmp_path / "data"))
    return tmp_path / "data"


@pytest.fixture(autouse=True)
def empty_clipboard(qapp):
    """Each test leaves the clipboard empty: the offscreen platform crashes when the process
    exits while the clipboard holds clips (test_clipboard's first test alone showed it)."""
    yield
    qapp.clipboard().clear()


@pytest.fixture(autouse=True)
def settings_home(qapp, tmp_path):
    """QSettings (recent files) go to an ini file under a temporary folder, as a test app."""
    from PySide6.QtCore import QSettings

    folder = tmp_path / "settings"
    qapp.setOrganizationName("haptic-timeline-tests")
    qapp.setApplicationName("editor-tests")
    QSettings.setDefaultFormat(QSettings.Format.IniFormat)
    QSettings.setPath(QSettings.Format.IniFormat, QSettings.Scope.UserScope, str(folder))
    return folder


def two_track_project() -> tuple[Project, dict[str, str]]:
    """Two drive tracks and a stiffness track; a 1 s sine clip at 0.5 s on the first."""
    project = edits.new_project()
    project, sine = edits.add_tile(project, generator("sine", 1.0, frequency=5), "Templates")
    project, ramp = edits.add_tile(project, generator("ramp", 0.5), "Templates")
    project, t1 = edits.add_track(project, "drive")
    project, t2 = edits.add_track(project, "drive")
    project, t3 = edits.add_track(project, "stiffness")
    project, c1 = edits.add_clip(project, t1, sine, 0.5)
    project, c2 = edits.add_clip(project, t2, ramp, 2.0)
    return project, {"t1": t1, "t2": t2, "t3": t3, "c1": c1, "c2": c2, "sine": sine, "ramp": ramp}


@pytest.fixture
def window(qtbot):
    """The main window on the two-track project at 200 px per second, snapping off."""
    from PySide6.QtWidgets import QMessageBox

    from timeline.gui.main_window import MainWindow

    project, ids = two_track_project()
    win = MainWindow(project)
    win.asked = 0

    def discard():
        win.asked += 1
        return QMessageBox.StandardButton.Discard

    win.ask_unsaved = discard
    qtbot.addWidget(win)
    win.resize(1300, 800)
    win.show()
    qtbot.waitExposed(win)
    win.view.lane_geometry.px_per_unit = 200.0
    win.view.snapping = False
    win.view.refresh()
    win.ids = ids
    # the first limits check starts after the first paint; its line in the message bar comes
    # before the test's own messages, as when it started with the window
    qtbot.waitUntil(lambda: win.findings.settled, timeout=20_000)
    yield win
    win.player.close()
    win.autosaver.discard()
