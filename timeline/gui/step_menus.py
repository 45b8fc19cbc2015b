"""Menus filled when opened: Edit > History (jump to a named undo step) and the Variants list."""

from __future__ import annotations

from PySide6.QtGui import QActionGroup
from PySide6.QtWidgets import QMenu

from .document import Document

SHOWN = 40  # the newest steps listed (older ones stay reachable by undo)


def fill_history(menu: QMenu, doc: Document) -> None:
    """Refill the menu from the document's history, each step named by what it changed."""
    menu.clear()
    group = QActionGroup(menu)
    names = doc.history.names
    first = max(0, len(names) - SHOWN)
    for index in range(len(names) - 1, first - 1, -1):
        action = menu.addAction(f"{index}. {names[index].replace('&', '&&')}")
        action.setCheckable(True)
        action.setChecked(index == doc.history.index)
        action.setToolTip("after this step" if index else "as opened")
        group.addAction(action)
        action.triggered.connect(lambda _=False, i=index: doc.go_to(i))


def fill_variants(menu: QMenu, doc: Document, switch) -> None:
    """List the variants, the active one checked; choosing one switches to it."""
    project = doc.project
    for action in [a for a in menu.actions() if a.property("variant")]:
        menu.removeAction(action)
    if not project.variants:
        empty = menu.addAction("(no variants yet: Ctrl+Shift+V saves one)")
        empty.setEnabled(False)
        empty.setProperty("variant", True)
        return
    group = QActionGroup(menu)
    for v in project.variants:
        action = menu.addAction(f"Variant {v.name}")
        action.setCheckable(True)
        action.setChecked(v.name == project.active_variant)
        action.setProperty("variant", True)
        group.addAction(action)
        action.triggered.connect(lambda _=False, name=v.name: switch(name))
