"""Undo, redo and history jumps name the step by what it changed."""

from __future__ import annotations

from PySide6.QtCore import QPoint

from .helpers import clip_point, drag


def test_undo_and_redo_name_the_step_in_seconds(window, qtbot):
    win = window
    start = clip_point(win, win.ids["c1"])
    drag(win, start, start + QPoint(100, 0))  # 200 px per second: 0.5 s later
    edit_menu = win.undo_action.associatedObjects()[0]
    edit_menu.popup(win.mapToGlobal(QPoint(10, 10)))
    qtbot.waitUntil(edit_menu.isVisible)
    assert win.undo_action.text() == "&Undo move 'sine' to 1 s"
    edit_menu.close()
    win.doc.undo()
    assert win.messages.text == "undid move 'sine' to 1 s"
    win.doc.redo()
    assert win.messages.text == "redid move 'sine' to 1 s"
    win.doc.go_to(0)
    assert win.messages.text == "back to step 0: open"
    win.doc.go_to(1)
    assert win.messages.text == "forward to step 1: move 'sine' to 1 s"
