"""Count the mouse and key events the GUI tests deliver (a pytest plugin, loaded on request).

QT_QPA_PLATFORM=offscreen python -m pytest tests/gui -p tests.gui.input_count -q
prints how many presses, releases, moves, double-clicks, key presses and context-menu events
reached widgets, one per event (a click is a press and a release; focus-proxy repeats count once).
"""

from __future__ import annotations

from collections import Counter

import pytest

COUNTED = {
    "MouseButtonPress",
    "MouseButtonRelease",
    "MouseButtonDblClick",
    "MouseMove",
    "KeyPress",
    "ContextMenu",
    "Wheel",
    "Drop",
}
_counts: Counter[str] = Counter()


@pytest.fixture(autouse=True)
def _count_input(qapp):
    from PySide6.QtCore import QObject
    from shiboken6 import getCppPointer

    last: list = [None, None, None]  # event address, type, receiver of the last counted event

    class Filter(QObject):
        def eventFilter(self, obj, event) -> bool:  # noqa: N802 (Qt's name)
            name = event.type().name
            if name not in COUNTED or not obj.isWidgetType():
                return False
            address = getCppPointer(event)[0]
            # an ignored event travels on to the parents: the same event, counted once
            propagated = obj is not last[2] and _contains(obj, last[2])
            if address == last[0] and name == last[1] and propagated:
                last[2] = obj
                return False
            last[:] = [address, name, obj]
            _counts[name] += 1
            return False

    counter = Filter()
    qapp.installEventFilter(counter)
    yield
    qapp.removeEventFilter(counter)


def _contains(parent, child) -> bool:
    try:
        return bool(parent.isAncestorOf(child))
    except (RuntimeError, TypeError):  # the earlier receiver is gone
        return False


def pytest_terminal_summary(terminalreporter) -> None:
    total = sum(_counts.values())
    parts = ", ".join(f"{k} {v}" for k, v in sorted(_counts.items()))
    terminalreporter.write_line(f"input events delivered by the GUI tests: {total} ({parts})")
