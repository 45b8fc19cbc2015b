"""File > Export's options, named as the command line names them: `--rate` and `--fixed-point`.

The rate is the sample rate of the written layers (the firmware's table step); a position
project gives it as a step in degrees (the project's own step is the default), which is the
CLI's `--rate` in samples per radian. Firmware tables (.h, .json) start at their format's default
step (one entry per degree or per millisecond, end to end) and the dialog shows their size as the
step changes; fixed point writes them as int16.
"""

from __future__ import annotations

import contextlib
import math
from pathlib import Path
from typing import Any

from PySide6.QtWidgets import (
    QCheckBox,
    QDialog,
    QDialogButtonBox,
    QDoubleSpinBox,
    QFormLayout,
    QLabel,
    QWidget,
)

from timeline.errors import HapticTimelineError
from timeline.model import Project
from timeline.plugins.file_formats import writer_for

FIRMWARE = (".h", ".json")
DEGREES = 180.0 / math.pi


class ExportOptions(QDialog):
    """Rate (or step) and fixed point for one export; `options()` gives export_project's."""

    def __init__(self, project: Project, path: Path, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setWindowTitle(f"Export {path.name}")
        self.axis = project.axis
        self.rate = QDoubleSpinBox()
        self.rate.setDecimals(4)
        if self.axis == "time":
            self.rate.setRange(1.0, 1e6)
            self.rate.setSuffix(" Hz")
            self.rate.setValue(project.rate)
            self.rate.setToolTip("Sample rate of the written layers (the CLI's --rate)")
            label = "rate (--rate)"
        else:
            self.rate.setRange(1e-4, 360.0)
            self.rate.setSuffix(" °")
            self.rate.setValue(DEGREES / project.rate)
            self.rate.setToolTip(
                "One value every this many degrees (the CLI's --rate is its inverse, per radian)"
            )
            label = "step (--rate)"
        self.fixed_point = QCheckBox("int16 tables with a scale each")
        self.fixed_point.setToolTip("Firmware tables (.h, .json) as int16 (CLI: --fixed-point)")
        self.fixed_point.setEnabled(path.suffix.lower() in FIRMWARE)
        self.default_rate = project.rate
        self.project = project
        # a firmware format's grid rule (found through its plugin): its default step and sizes
        self.grid = (
            getattr(writer_for(path), "grid", None) if path.suffix.lower() in FIRMWARE else None
        )
        self.table_size = QLabel()
        if self.grid is not None:
            self.rate.valueChanged.connect(self.show_size)
            self.fixed_point.toggled.connect(self.show_size)
            # nothing to export yet: the project's step stays, and the size says why
            with contextlib.suppress(HapticTimelineError):
                self.default_rate = 1.0 / self.grid(project).step
            step = self.default_rate if self.axis == "time" else DEGREES / self.default_rate
            self.rate.setValue(step)
            self.show_size()
        form = QFormLayout(self)
        form.addRow(QLabel(f"Export the design to {path.name}"))
        form.addRow(label, self.rate)
        form.addRow("fixed point (--fixed-point)", self.fixed_point)
        if self.grid is not None:
            form.addRow("size", self.table_size)
        buttons = QDialogButtonBox(
            QDialogButtonBox.StandardButton.Ok | QDialogButtonBox.StandardButton.Cancel
        )
        buttons.accepted.connect(self.accept)
        buttons.rejected.connect(self.reject)
        form.addRow(buttons)

    def show_size(self) -> None:
        """Say the firmware tables' entries and bytes at the chosen step."""
        try:
            grid = self.grid(self.project, self.chosen_rate())  # type: ignore[misc]
        except HapticTimelineError as exc:
            self.table_size.setText(str(exc))
            return
        fixed = self.fixed_point.isChecked()
        self.table_size.setText(
            f"{grid.count:,} entries a table, end to end: "
            f"{grid.count * (2 if fixed else 4):,} bytes each as {'int16' if fixed else 'float32'}"
        )

    def chosen_rate(self) -> float:
        """The rate in the project's axis units (per second, or per radian)."""
        value = self.rate.value()
        return value if self.axis == "time" else DEGREES / value

    def options(self) -> dict[str, Any]:
        """export_project's keyword options: rate only if changed, fixed point if ticked."""
        found: dict[str, Any] = {}
        rate = self.chosen_rate()
        if not math.isclose(rate, self.default_rate, rel_tol=1e-6):
            found["rate"] = rate
        if self.fixed_point.isEnabled() and self.fixed_point.isChecked():
            found["fixed_point"] = True
        return found
