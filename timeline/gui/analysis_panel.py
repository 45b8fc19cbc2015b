"""The sound analysis's settings panel: every analysis setting as a field, in the import dock.

Built the first time the dock is shown (`SoundImport.panel`), so neither its widgets nor the
analysis settings load before the editor's first paint.
"""

from __future__ import annotations

from dataclasses import fields

from PySide6.QtCore import Signal
from PySide6.QtWidgets import (
    QCheckBox,
    QDoubleSpinBox,
    QFormLayout,
    QLabel,
    QPushButton,
    QScrollArea,
    QSpinBox,
    QVBoxLayout,
    QWidget,
)

from timeline.analysis import DEFAULTS, AnalysisSettings
from timeline.errors import SettingsError

FIRST = ("sensitivity", "resolution", "emphasis", "adaptive", "ducking")  # at the panel's top
# spin-box ranges and decimals for the numeric settings (unit suffix from the help text)
RANGES = {
    "rms_window": (0.0, 0.1, 5), "attack": (0.0, 1.0, 5), "hold": (0.0, 1.0, 4),
    "release": (0.0, 5.0, 3), "update": (1e-4, 0.1, 4), "level_db": (-60.0, 0.0, 1),
    "gain_db": (-60.0, 40.0, 1), "centroid_lowpass": (10.0, 20000.0, 0),
    "frequency_min": (0.0, 20000.0, 0), "frequency_max": (1.0, 20000.0, 0),
    "output_min": (0.0, 1.0, 2), "output_max": (0.0, 1.0, 2), "minimum_score": (0.0, 1.0, 9),
    "tolerance": (0.0, 1.0, 3), "resolution": (0.0, 100.0, 0), "sensitivity": (0.0, 100.0, 0),
    "peak_window": (0.0, 2.0, 3),
    "minimum_rise": (0.0, 1.0, 2), "plateau": (0.0, 100.0, 0), "sharpness_min": (0.0, 1.0, 2),
    "sharpness_max": (0.0, 1.0, 2), "ducking": (0.0, 100.0, 0), "tail_db": (0.0, 120.0, 1),
    "tail_ratio": (1.0, 100.0, 1),
}  # fmt: skip
INT_RANGES = {
    "fft_size": (16, 65536),
    "overlap": (1, 64),
    "amplitude_points_per_second": (2, 1000),
    "frequency_points_per_second": (2, 1000),
}


LABELS = {
    "rms_window": "RMS window (s)", "attack": "Attack (s)", "hold": "Hold (s)",
    "release": "Release (s)", "update": "Update every (s)", "normalize": "Normalise",
    "level_db": "Level (dBFS)", "gain_db": "Gain (dB)", "fft_size": "FFT size",
    "overlap": "Overlap", "centroid_lowpass": "Centroid below (Hz)",
    "frequency_min": "Frequency 0 at (Hz)", "frequency_max": "Frequency 1 at (Hz)",
    "output_min": "Lowest frequency", "output_max": "Highest frequency",
    "amplitude_points_per_second": "Amplitude points / s",
    "frequency_points_per_second": "Frequency points / s", "minimum_score": "Minimum score",
    "tolerance": "Error bound", "resolution": "Resolution (%)", "emphasis": "Emphasis",
    "adaptive": "Adaptive emphasis", "sensitivity": "Sensitivity (%)",
    "peak_window": "Peak window (s)", "minimum_rise": "Minimum rise", "plateau": "Plateau (%)",
    "sharpness_min": "Softest hit frequency", "sharpness_max": "Sharpest hit frequency",
    "ducking": "Ducking (%)", "tail_db": "Tail below (dB)", "tail_ratio": "Tail ratio",
}  # fmt: skip


Field = QCheckBox | QSpinBox | QDoubleSpinBox  # one analysis setting's editor


def _label(name: str) -> str:
    return LABELS.get(name, name.replace("_", " ").capitalize())


class AnalysisPanel(QWidget):
    """Every analysis setting as a field; `settings()` reads them (or raises SettingsError)."""

    changed = Signal()

    def __init__(self) -> None:
        super().__init__()
        form = QFormLayout()
        self.fields: dict[str, Field] = {}
        rest = [f.name for f in fields(AnalysisSettings) if f.name not in FIRST]
        for name in (*FIRST, *rest):
            widget = self._field(name, getattr(DEFAULTS, name))
            widget.setToolTip(AnalysisSettings.help(name))
            widget.setMaximumWidth(150)
            form.addRow(_label(name), widget)
            self.fields[name] = widget
        self.error = QLabel("")
        self.error.setStyleSheet("color: #b00020;")
        self.error.setWordWrap(True)
        defaults = QPushButton("Defaults")
        defaults.setToolTip("Put every setting back to its default (docs/convert.md)")
        defaults.clicked.connect(self.restore_defaults)
        inner = QWidget()
        inner.setLayout(form)
        scroll = QScrollArea()
        scroll.setWidget(inner)
        scroll.setWidgetResizable(True)
        layout = QVBoxLayout(self)
        layout.addWidget(scroll, 1)
        layout.addWidget(self.error)
        layout.addWidget(defaults)

    def _field(self, name: str, value: object) -> Field:
        if isinstance(value, bool):
            box = QCheckBox()
            box.toggled.connect(self.changed)
            return box
        if name in INT_RANGES:
            spin = QSpinBox()
            spin.setRange(*INT_RANGES[name])
            spin.valueChanged.connect(self.changed)
            return spin
        lo, hi, decimals = RANGES[name]
        number = QDoubleSpinBox()
        number.setRange(lo, hi)
        number.setDecimals(decimals)
        number.setSingleStep(10.0 ** -min(decimals, 3) if hi > 1 else 0.01)
        if name == "tolerance":
            number.setSpecialValueText("off")
        number.valueChanged.connect(self.changed)
        return number

    def restore_defaults(self) -> None:
        """The default settings in every field."""
        self.show_settings(DEFAULTS)

    def show_settings(self, settings: AnalysisSettings) -> None:
        for name, widget in self.fields.items():
            value = getattr(settings, name)
            if isinstance(widget, QCheckBox):
                widget.setChecked(bool(value))
            else:
                widget.setValue(0 if value is None else value)
        self.error.setText("")

    def settings(self) -> AnalysisSettings:
        """The settings in the fields; a SettingsError (also shown in the panel) if they clash."""
        values = {}
        for name, widget in self.fields.items():
            if isinstance(widget, QCheckBox):
                values[name] = widget.isChecked()
            else:
                values[name] = widget.value()
        values["tolerance"] = values["tolerance"] or None
        try:
            found = AnalysisSettings(**values)
        except SettingsError as exc:
            self.error.setText(str(exc))
            raise
        self.error.setText("")
        return found
