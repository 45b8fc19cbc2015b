"""The message bar: status and errors in one line at the bottom, never a modal pop-up.

A message longer than the bar is shown up to an ellipsis with the whole sentence in the tooltip
(one line always, so the lanes never jump while a message shows); `text` is always the whole.

An error or an outcome (a job cancelled, a step of the history taken) is held for HOLD_SECONDS
against routine status (the limits check's summary): a check that ends just after an import
failed would otherwise replace the failure before anyone read it. Routine status arriving while
a message is held waits for the hold to end, and is dropped if another message comes first.
"""

from __future__ import annotations

from PySide6.QtCore import QSize, Qt, QTimer, Signal
from PySide6.QtGui import QResizeEvent
from PySide6.QtWidgets import QHBoxLayout, QLabel, QProgressBar, QPushButton, QWidget

COLOURS = {"info": "#1f1f1f", "error": "#b00020", "hint": "#6b6b6b"}
INFO_SECONDS = 6
HOLD_SECONDS = 4
HINT = "Drag a tile from the palette onto a track · Space plays · Ctrl+Z undoes"


class ElidedLabel(QLabel):
    """One line of text that ends in "…" when it does not fit; the whole is in its tooltip."""

    def __init__(self) -> None:
        super().__init__()
        self.whole = ""

    def set_whole(self, text: str) -> None:
        self.whole = text
        self._fit()

    def resizeEvent(self, event: QResizeEvent) -> None:  # noqa: N802 - Qt's name
        super().resizeEvent(event)
        self._fit()

    def minimumSizeHint(self) -> QSize:  # noqa: N802 - Qt's name
        """Any width will do: the text is elided, never the window widened."""
        return QSize(0, super().minimumSizeHint().height())

    def sizeHint(self) -> QSize:  # noqa: N802 - Qt's name
        return QSize(0, super().sizeHint().height())

    def _fit(self) -> None:
        metrics = self.fontMetrics()
        shown = metrics.elidedText(self.whole, Qt.TextElideMode.ElideRight, self.width())
        self.setText(shown)
        self.setToolTip(self.whole if shown != self.whole else "")


class MessageBar(QWidget):
    """One line of text (errors in red), an optional action button, progress with Cancel."""

    cancel_requested = Signal()

    def __init__(self) -> None:
        super().__init__()
        self.setObjectName("messageBar")
        self.setAttribute(Qt.WidgetAttribute.WA_StyledBackground)
        self.setStyleSheet("#messageBar { background: #eef0f3; border-top: 1px solid #c4c8ce; }")
        self.setMinimumHeight(28)
        layout = QHBoxLayout(self)
        layout.setContentsMargins(8, 2, 8, 2)
        self.label = ElidedLabel()
        self.label.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
        self.action = QPushButton()
        self.action.hide()
        self.progress = QProgressBar()
        self.progress.setMaximumWidth(220)
        self.progress.setRange(0, 1000)
        self.progress.hide()
        self.cancel = QPushButton("Cancel")
        self.cancel.hide()
        for button in (self.action, self.cancel):  # both hide once clicked: keep the focus where
            button.setFocusPolicy(Qt.FocusPolicy.NoFocus)  # it was (not a track name's text)
        self.cancel.clicked.connect(self.cancel_requested)
        layout.addWidget(self.label, 1)
        layout.addWidget(self.action)
        layout.addWidget(self.progress)
        layout.addWidget(self.cancel)
        self.history: list[tuple[str, str]] = []
        self._clear = QTimer(self)
        self._clear.setSingleShot(True)
        self._clear.timeout.connect(self.show_hint)
        self._hold = QTimer(self)
        self._hold.setSingleShot(True)
        self._hold.timeout.connect(self._show_pending)
        self._pending: tuple[str, str] | None = None
        self._callback = None
        self.action.clicked.connect(self._run_action)
        self.show_hint()

    @property
    def text(self) -> str:
        """The whole message (the bar may show it elided)."""
        return self.label.whole

    def show_message(self, text: str, level: str = "info", hold: bool = False) -> None:
        """Show a sentence; info fades after a few seconds, errors stay until the next message.
        An error, or a message shown with `hold`, is not replaced by routine status for
        HOLD_SECONDS."""
        self._pending = None
        if hold or level == "error":
            self._hold.start(HOLD_SECONDS * 1000)
        else:
            self._hold.stop()
        self.history.append((text, level))
        self.label.set_whole(text)
        self.label.setStyleSheet(f"color: {COLOURS.get(level, COLOURS['info'])};")
        if level == "info":
            self._clear.start(INFO_SECONDS * 1000)
        else:
            self._clear.stop()

    def show_routine(self, text: str, level: str = "info") -> None:
        """Show routine status (a check's summary), or keep it until a held message's time is
        up."""
        if self._hold.isActive():
            self._pending = (text, level)
        else:
            self.show_message(text, level)

    def _show_pending(self) -> None:
        pending, self._pending = self._pending, None
        if pending is not None:
            self.show_message(*pending)

    def show_hint(self) -> None:
        """Between messages, say in grey what to do next (not recorded in the history)."""
        self.label.set_whole(HINT)
        self.label.setStyleSheet(f"color: {COLOURS['hint']};")

    def offer(self, text: str, button: str, callback) -> None:
        """Show a message with a button (e.g. Recover) that runs callback once."""
        self.show_message(text, "info")
        self._clear.stop()
        self._callback = callback
        self.action.setText(button)
        self.action.show()

    def _run_action(self) -> None:
        callback, self._callback = self._callback, None
        self.action.hide()
        if callback:
            callback()

    def set_progress(self, fraction: float | None) -> None:
        """Show a progress fraction with Cancel, or hide both (None)."""
        busy = fraction is not None
        self.progress.setVisible(busy)
        self.cancel.setVisible(busy)
        if busy:
            self.progress.setValue(int(max(0.0, min(1.0, fraction)) * 1000))
