"""The Help menu: the keyboard shortcuts, listed from the window's actions, and first steps.

The shortcut list is read from the QActions themselves each time it opens, so it cannot drift
from what the keys do. The first-steps text is also in docs/editor.md ("First steps").
"""

from __future__ import annotations

from PySide6.QtGui import QAction, QKeySequence
from PySide6.QtWidgets import (
    QDialog,
    QDialogButtonBox,
    QMainWindow,
    QMenu,
    QTextBrowser,
    QVBoxLayout,
    QWidget,
)

FIRST_STEPS = """
<h3>First steps</h3>
<ol>
<li><b>Place a tile.</b> Drag a tile from the palette (left) onto a track's lane. The track's
kind gives it meaning: a drive track plays it as torque, a stiffness track as a spring.</li>
<li><b>Play and feel it.</b> Press <b>Space</b>. The scope (bottom right) shows the knob's
angle and torque; choose what the hand does (hold, free, turn, push) beside the device.</li>
<li><b>Shape it.</b> Drag a clip to move it, its edges to trim (Shift: stretch), the square
handles at its top corners for fades, Shift-drag its body up or down for amplitude. Set its
mirror line with a right-click (<i>Set mirror line here</i>) or Ctrl+Shift+click.</li>
<li><b>Type exact numbers.</b> The inspector (beside the shape editor) takes typed values;
the shape editor below the lanes edits the tile's points.</li>
<li><b>Compare.</b> <b>Ctrl+Shift+V</b> saves the design as a variant (A, B, ...) and
<b>V</b> switches between them, to compare by feel.</li>
<li><b>Undo anything.</b> <b>Ctrl+Z</b> undoes one step; Edit &gt; History jumps to any step
by name. Variants survive every undo.</li>
<li><b>Save and export.</b> <b>Ctrl+S</b> saves the project (.htl); <b>Ctrl+E</b> exports it
(AHAP, .haptic, WAV, CSV, firmware tables, ...), with the command line's options.</li>
</ol>
"""


def menu_paths(window: QMainWindow) -> dict[QAction, str]:
    """Each menu action's place, "Edit > Fade shape" (actions seen in menu order)."""
    found: dict[QAction, str] = {}

    def walk(menu: QMenu, path: str) -> None:
        for action in menu.actions():
            sub = action.menu()
            if isinstance(sub, QMenu):
                walk(sub, f"{path} > {plain(action.text())}")
            else:
                found.setdefault(action, path)

    for action in window.menuBar().actions():
        sub = action.menu()
        if isinstance(sub, QMenu):
            walk(sub, plain(action.text()))
    return found


def plain(text: str) -> str:
    """A menu text without its mnemonic ampersands."""
    return text.replace("&&", "\0").replace("&", "").replace("\0", "&")


def shortcut_rows(window: QMainWindow) -> list[tuple[str, str, str]]:
    """(keys, action, where) for every action of the window that has a shortcut, menu order
    first, then actions that live on a region of the window (named by its class)."""
    paths = menu_paths(window)
    actions = [a for a in paths if a.shortcuts()]
    actions += [a for a in window.findChildren(QAction) if a.shortcuts() and a not in paths]
    rows = []
    for action in actions:
        keys = " or ".join(
            k.toString(QKeySequence.SequenceFormat.NativeText) for k in action.shortcuts()
        )
        where = paths.get(action) or type(action.parent()).__name__
        rows.append((keys, plain(action.text()), where))
    return rows


def shortcuts_html(window: QMainWindow) -> str:
    """The shortcut list as an HTML table."""
    import html  # with html.entities, ~5 ms: not on the way to the editor's first paint

    cells = "".join(
        f"<tr><td><b>{html.escape(k)}</b></td><td>{html.escape(a)}</td>"
        f"<td style='color:#666'>{html.escape(w)}</td></tr>"
        for k, a, w in shortcut_rows(window)
    )
    return (
        "<h3>Keyboard shortcuts</h3><table cellspacing='0' cellpadding='3'>"
        f"<tr><th align='left'>Keys</th><th align='left'>Does</th>"
        f"<th align='left'>Menu</th></tr>{cells}</table>"
    )


def help_dialog(parent: QWidget, title: str, text: str) -> QDialog:
    """A non-modal page of rich text with a Close button."""
    dialog = QDialog(parent)
    dialog.setWindowTitle(title)
    browser = QTextBrowser()
    browser.setHtml(text)
    buttons = QDialogButtonBox(QDialogButtonBox.StandardButton.Close)
    buttons.rejected.connect(dialog.close)
    layout = QVBoxLayout(dialog)
    layout.addWidget(browser)
    layout.addWidget(buttons)
    dialog.browser = browser  # type: ignore[attr-defined]
    dialog.resize(620, 560)
    return dialog


class HelpMenu:
    """Help > Keyboard shortcuts and Help > First steps (in the window's Help `menu`); each opens
    its page beside the window."""

    def __init__(self, window: QMainWindow, menu: QMenu) -> None:
        self.window = window
        self.page: QDialog | None = None
        self.menu = menu
        self.shortcuts_action = menu.addAction("&Keyboard shortcuts", self.show_shortcuts)
        self.shortcuts_action.setShortcut(QKeySequence("F1"))
        self.first_steps_action = menu.addAction("&First steps", self.show_first_steps)

    def show_shortcuts(self) -> QDialog:
        return self._show("Keyboard shortcuts", shortcuts_html(self.window))

    def show_first_steps(self) -> QDialog:
        return self._show("First steps", FIRST_STEPS)

    def _show(self, title: str, text: str) -> QDialog:
        if self.page is not None:
            self.page.close()
        self.page = help_dialog(self.window, title, text)
        self.page.show()
        return self.page
