"""Help: the shortcut list comes from the actions themselves; a first-steps page."""

from __future__ import annotations

from PySide6.QtGui import QAction, QKeySequence

from timeline.gui.help import FIRST_STEPS, plain, shortcut_rows

NATIVE = QKeySequence.SequenceFormat.NativeText


def test_every_action_with_a_shortcut_is_listed_with_its_keys(window):
    rows = shortcut_rows(window)
    listed = {(action, keys) for keys, action, _ in rows}
    with_keys = [a for a in window.findChildren(QAction) if a.shortcuts()]
    assert len(with_keys) >= 30  # the window's menus are full of shortcuts
    for action in with_keys:
        keys = " or ".join(k.toString(NATIVE) for k in action.shortcuts())
        assert (plain(action.text()), keys) in listed
    assert ("Ctrl+Z", "Undo", "Edit") in rows
    assert ("S or Ctrl+I", "Split at playhead", "Edit") in rows
    assert len(rows) == len(with_keys)


def test_a_new_shortcut_appears_in_the_list_without_editing_it(window):
    action = QAction("&Frobnicate", window)
    action.setShortcut(QKeySequence("Ctrl+Shift+F"))
    window.view_menu.addAction(action)
    assert ("Ctrl+Shift+F", "Frobnicate", "View") in shortcut_rows(window)


def test_the_help_menu_opens_the_shortcuts_and_first_steps(window, qtbot):
    page = window.help.show_shortcuts()
    text = page.browser.toPlainText()
    assert "Ctrl+Shift+V" in text and "Save design as variant" in text and "F1" in text
    page = window.help.show_first_steps()
    assert "First steps" in page.browser.toPlainText()
    assert "Ctrl+Shift+click" in FIRST_STEPS
    menus = [plain(a.text()) for a in window.menuBar().actions()]
    assert menus[-1] == "Help"
