"""Transport: play / stop / loop of the project or the selected tracks, device and hand, scope."""

from __future__ import annotations

from PySide6.QtWidgets import (
    QCheckBox,
    QComboBox,
    QHBoxLayout,
    QLabel,
    QPushButton,
    QVBoxLayout,
    QWidget,
)

from timeline.devices import HAND_MODES, Hand

from .geometry import axis_text
from .player import Player
from .scope import Scope


class Transport(QWidget):
    """The play controls and the live scope; the window decides what to play."""

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
        self.hand.currentTextChanged.connect(self._set_hand)
        self.where = QLabel()
        self.where.setMinimumWidth(70)
        self.where.setToolTip("Where the playhead is")
        self.show_position(0.0, "time")
        self.scope = Scope()
        row = QHBoxLayout()
        for widget in (self.play_button, self.loop, self.selected_only):
            row.addWidget(widget)
        row.addStretch(1)
        row.addWidget(QLabel("device"))
        row.addWidget(self.device)
        row.addWidget(QLabel("hand"))
        row.addWidget(self.hand)
        row.addWidget(QLabel("playhead"))
        row.addWidget(self.where)
        layout = QVBoxLayout(self)
        layout.setContentsMargins(4, 2, 4, 2)
        layout.addLayout(row)
        layout.addWidget(self.scope, 1)
        player.telemetry.connect(self.scope.add)
        player.finished.connect(lambda _: self.show_playing(False))

    def _set_hand(self, mode: str) -> None:
        self.player.hand = Hand.parse(mode)

    def show_playing(self, playing: bool) -> None:
        """Show the Play button's state."""
        self.play_button.setText("■ Stop" if playing else "▶ Play")

    def show_position(self, u: float, axis: str) -> None:
        """Show the playhead position in seconds, or degrees in a position project."""
        self.where.setText(axis_text(u, axis, ".3f" if axis == "time" else ".1f"))
