"""Transport: play / stop / loop of the project or the selected tracks, device and hand, scope."""

from __future__ import annotations

from PySide6.QtCore import Qt, Signal
from PySide6.QtWidgets import (
    QCheckBox,
    QComboBox,
    QDoubleSpinBox,
    QHBoxLayout,
    QLabel,
    QPushButton,
    QVBoxLayout,
    QWidget,
)

from timeline.plugins.device_protocol import HAND_MODELS, HAND_MODES, Hand
from timeline.plugins.device_protocol.hand import DEFAULT_PUSH_MNM, DEFAULT_TURN_DEG_PER_S

from .flow_layout import FlowLayout
from .geometry import axis_text
from .player import Player
from .scope import Scope

HAND_TIPS = {
    "hold": "The hand holds the knob still",
    "free": "The hand lets go: the knob moves only by its own torque",
    "turn": "The hand turns the knob at a speed (°/s; negative turns back)",
    "push": "The hand pushes the knob with a torque (mNm; negative pushes back)",
}


class Transport(QWidget):
    """The play controls and the live scope; the window decides what to play."""

    hand_changed = Signal(object)  # the new Hand

    def __init__(self, player: Player) -> None:
        super().__init__()
        self.player = player
        self.play_button = QPushButton("▶ Play")
        self.play_button.setToolTip("Play or stop (Space)")
        self.loop = QCheckBox("Loop")
        self.selected_only = QCheckBox("Selected tracks")
        self.selected_only.setToolTip("Play only the tracks of the selected clips")
        self.device = QComboBox()
        self.device.addItems(player.devices() or ["sim"])
        self.device.setCurrentText(player.device_name)
        self.device.setToolTip("Output device (from the device plugins)")
        self.device.currentTextChanged.connect(player.choose_device)
        self.hand = QComboBox()
        self.hand.addItems(list(HAND_MODES))
        self.hand.setToolTip("What the simulated hand does while playing")
        for i, mode in enumerate(HAND_MODES):
            self.hand.setItemData(i, HAND_TIPS[mode], Qt.ItemDataRole.ToolTipRole)
        self.hand_value = QDoubleSpinBox()
        self.hand_value.setDecimals(1)
        self.hand_value.setKeyboardTracking(False)
        self.hand_model = QComboBox()
        self.hand_model.addItems(list(HAND_MODELS))
        self.hand_model.setToolTip("Whose hand: its grip stiffness, damping and inertia")
        for i, model in enumerate(HAND_MODELS.values()):
            tip = f"{model.name}: {model.source}"
            self.hand_model.setItemData(i, tip, Qt.ItemDataRole.ToolTipRole)
        self.hand_model.currentTextChanged.connect(lambda _: self._set_hand())
        self.hand.currentTextChanged.connect(self._mode_chosen)
        self.hand_value.valueChanged.connect(lambda _: self._set_hand())
        self._mode_chosen(self.hand.currentText())
        self.where = QLabel()
        self.where.setMinimumWidth(self.where.fontMetrics().horizontalAdvance("-00000.000 s"))
        self.where.setToolTip("Where the playhead is")
        self.show_position(0.0, "time")
        self.scope = Scope()
        # groups of controls flow into as many rows as the width needs (a 1024-pixel window)
        self.groups = [
            _group(self.play_button, self.loop, self.selected_only),
            _group(QLabel("playhead"), self.where),
            _group(QLabel("device"), self.device),
            _group(QLabel("hand"), self.hand_model, self.hand, self.hand_value),
        ]
        rows = FlowLayout(spacing=8)
        for group in self.groups:
            rows.addWidget(group)
        layout = QVBoxLayout(self)
        layout.setContentsMargins(4, 2, 4, 2)
        layout.addLayout(rows)
        layout.addWidget(self.scope, 1)
        player.telemetry.connect(self.scope.add)
        player.finished.connect(lambda _: self.show_playing(False))

    def _mode_chosen(self, mode: str) -> None:
        """Show the speed (turn) or torque (push) box with its unit and a sensible default."""
        box = self.hand_value
        box.blockSignals(True)
        if mode == "turn":
            box.setRange(-3600.0, 3600.0)
            box.setSuffix(" °/s")
            box.setValue(DEFAULT_TURN_DEG_PER_S)
        elif mode == "push":
            box.setRange(-500.0, 500.0)
            box.setSuffix(" mNm")
            box.setValue(DEFAULT_PUSH_MNM)
        box.blockSignals(False)
        box.setVisible(mode in ("turn", "push"))
        box.setToolTip(HAND_TIPS[mode])
        self._set_hand()

    def _set_hand(self) -> None:
        mode = self.hand.currentText()
        value = self.hand_value.value() if mode in ("turn", "push") else 0.0
        self.player.hand = Hand(mode, value, model=self.hand_model.currentText())
        self.hand_changed.emit(self.player.hand)

    def show_playing(self, playing: bool) -> None:
        """Show the Play button's state."""
        self.play_button.setText("■ Stop" if playing else "▶ Play")
        self.scope.waiting = playing
        self.scope.update()

    def show_position(self, u: float, axis: str) -> None:
        """Show the playhead position in seconds, or degrees in a position project."""
        self.where.setText(axis_text(u, axis, ".3f" if axis == "time" else ".1f"))


def _group(*widgets: QWidget) -> QWidget:
    """Controls that stay together on one row of the transport."""
    group = QWidget()
    row = QHBoxLayout(group)
    row.setContentsMargins(0, 0, 0, 0)
    for widget in widgets:
        row.addWidget(widget)
    return group
