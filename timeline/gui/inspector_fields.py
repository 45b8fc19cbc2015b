"""The inspector's number fields: a value shown in the project's display units (s, or degrees in
a position project), typed exactly, and committed as one edit only when it really changed."""

from __future__ import annotations

import math
from collections.abc import Callable

from PySide6.QtCore import Qt
from PySide6.QtWidgets import QDoubleSpinBox, QHBoxLayout, QWidget

from . import quiet

AXIS_DECIMALS = {"time": 4, "position": 3}  # 0.1 ms, or a thousandth of a degree
MIN_WIDTH = 64


def shown_axis(u: float, axis: str) -> float:
    """An axis value (s or rad) as the editor shows it (s or degrees)."""
    return math.degrees(u) if axis == "position" else u


def axis_value(shown: float, axis: str) -> float:
    """A shown value back in axis units: math.radians, so 20 degrees is exactly radians(20)."""
    return math.radians(shown) if axis == "position" else shown


def axis_suffix(axis: str) -> str:
    return " s" if axis == "time" else "°"


class NumberField(QDoubleSpinBox):
    """A spin box that calls `commit(value)` on Enter (or leaving it) when the typed value
    differs from the one shown: leaving an untouched box changes nothing."""

    def __init__(
        self,
        commit: Callable[[float], None],
        decimals: int = 3,
        suffix: str = "",
        prefix: str = "",
        bounds: tuple[float, float] = (-1e9, 1e9),
        tip: str = "",
    ) -> None:
        super().__init__()
        self.commit = commit
        self.setDecimals(decimals)
        self.setRange(*bounds)
        self.setSuffix(suffix)
        self.setPrefix(prefix)
        self.setKeyboardTracking(False)
        self.setFocusPolicy(Qt.FocusPolicy.StrongFocus)  # the wheel scrolls the page, not values
        self.setMinimumWidth(MIN_WIDTH)  # not as wide as the largest value: the pane stays narrow
        self.setToolTip(f"{tip}; type a value and press Enter" if tip else "type and press Enter")
        self._shown: float | None = None
        self.editingFinished.connect(self._finished)

    def show_value(self, value: float) -> None:
        """Show a value (rounded to the box's decimals) without committing it."""
        quiet.show_value(self, value)
        self._shown = self.value()

    def _finished(self) -> None:
        if self._shown is not None and self.value() == self._shown:
            return
        self._shown = self.value()
        self.commit(self.value())


def pair(*widgets: QWidget) -> QWidget:
    """Widgets side by side in one form row (numbers get the most room)."""
    row = QWidget()
    layout = QHBoxLayout(row)
    layout.setContentsMargins(0, 0, 0, 0)
    layout.setSpacing(4)
    for widget in widgets:
        layout.addWidget(widget, 3 if isinstance(widget, QDoubleSpinBox) else 2)
    return row
