"""The window remembers its size, splitters, docks and hand between sessions (QSettings)."""

from __future__ import annotations

from PySide6.QtCore import QSettings

from timeline.gui.main_window import MainWindow


def reopened(qtbot) -> MainWindow:
    win = MainWindow()
    qtbot.addWidget(win)
    win.show()
    qtbot.waitExposed(win)
    return win


def test_a_new_window_remembers_size_splitters_and_hand(window, qtbot, settings_home):
    window.resize(1100, 720)
    window.show()
    qtbot.waitUntil(lambda: window.width() == 1100)
    window.top_split.setSizes([250, 850])
    window.bottom_split.setSizes([400, 200, 500])
    window.sound_import.dock.show()
    t = window.transport
    t.hand_model.setCurrentIndex(t.hand_model.count() - 1)
    t.hand.setCurrentText("turn")
    t.hand_value.setValue(-45.0)
    top, bottom = window.top_split.sizes(), window.bottom_split.sizes()
    model = t.hand_model.currentText()
    window.close()
    assert (settings_home / "haptic-timeline-tests" / "editor-tests.ini").exists()

    again = reopened(qtbot)
    assert again.restored
    assert (again.width(), again.height()) == (1100, 720)
    assert again.top_split.sizes() == top and again.bottom_split.sizes() == bottom
    assert again.sound_import.dock.isVisible()
    assert again.sound_import.dock.widget() is again.sound_import._panel is not None  # built
    h = again.transport
    assert (h.hand_model.currentText(), h.hand.currentText()) == (model, "turn")
    assert h.hand_value.value() == -45.0
    assert again.player.hand.mode == "turn" and again.player.hand.value == -45.0
    again.close()


def test_a_first_session_opens_at_the_default_size(qtbot):
    assert QSettings().allKeys() == []
    win = MainWindow()
    qtbot.addWidget(win)
    assert not win.restored
    assert (win.width(), win.height()) == (1400, 860)
    assert win.transport.hand.currentText() == "hold"


def test_a_remembered_place_on_the_screen_is_kept(window):
    from PySide6.QtCore import QRect

    from timeline.gui.app import fit_to_screen

    window.resize(1000, 600)
    window.move(120, 90)
    fit_to_screen(window, QRect(0, 24, 1280, 776), keep_place=True)
    assert (window.x(), window.y(), window.width(), window.height()) == (120, 90, 1000, 600)
    window.move(900, 90)  # remembered from a wider screen: it would stick out
    fit_to_screen(window, QRect(0, 24, 1280, 776), keep_place=True)
    assert (window.x(), window.y()) == (0, 24)
