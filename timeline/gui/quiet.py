"""Setters that leave a widget alone when it already shows what it is given.

Qt lays a spin box out again on every setPrefix, setSuffix, setDecimals or setRange and repaints
it on every setValue, even when nothing changes; the layout request climbs to the window, so a
clip drag that refreshed the panels with their unchanged values repainted the whole window on
each mouse move. These setters change a widget only when what it shows would change, and never
emit its signals.
"""

from __future__ import annotations

from PySide6.QtWidgets import QAbstractButton, QDoubleSpinBox, QLabel, QLineEdit


def show_value(box: QDoubleSpinBox, value: float) -> None:
    """Show a value (rounded to the box's decimals, clamped to its range) without signals."""
    if box.minimum() <= value <= box.maximum() and box.textFromValue(value) == box.textFromValue(
        box.value()
    ):
        return
    box.blockSignals(True)
    box.setValue(value)
    box.blockSignals(False)


def set_format(
    box: QDoubleSpinBox,
    *,
    decimals: int | None = None,
    prefix: str | None = None,
    suffix: str | None = None,
    minimum: float | None = None,
) -> None:
    """Change a spin box's decimals, prefix, suffix or minimum where they differ."""
    if decimals is not None and box.decimals() != decimals:
        box.setDecimals(decimals)
    if prefix is not None and box.prefix() != prefix:
        box.setPrefix(prefix)
    if suffix is not None and box.suffix() != suffix:
        box.setSuffix(suffix)
    if minimum is not None and box.minimum() != minimum:
        box.setMinimum(minimum)


def set_text(widget: QLabel | QLineEdit, text: str) -> None:
    """Set a label's or line edit's text where it differs (a line edit resets its cursor)."""
    if widget.text() != text:
        widget.setText(text)


def set_checked(button: QAbstractButton, on: bool) -> None:
    """Check or uncheck a button without signals."""
    if button.isChecked() != on:
        button.blockSignals(True)
        button.setChecked(on)
        button.blockSignals(False)
