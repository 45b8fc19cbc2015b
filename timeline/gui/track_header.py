"""Track headers beside the lanes: name, kind colour and label, unit, gain, mute, solo, remove.
Click a header to show its track in the inspector; drag it up or down to reorder the tracks."""

from __future__ import annotations

from typing import Any

from PySide6.QtCore import QEvent, QObject, QPoint, Qt, Signal
from PySide6.QtGui import QColor, QMouseEvent
from PySide6.QtWidgets import (
    QDoubleSpinBox,
    QFrame,
    QHBoxLayout,
    QLabel,
    QLineEdit,
    QMenu,
    QPushButton,
    QScrollArea,
    QToolButton,
    QVBoxLayout,
    QWidget,
)

from timeline import edits
from timeline.model import Track
from timeline.plugins.track_kinds import kinds_for_axis, track_kind

from . import quiet
from .document import Document
from .geometry import LANE_HEIGHT

WIDTH = 270
DRAG_PX = 4  # a header moved less than this was clicked, not dragged


class TrackHeader(QFrame):
    """The header of one track; every change is one edit through the document."""

    def __init__(self, doc: Document, track: Track, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.doc = doc
        self.track_id = track.id
        kind = track_kind(track.kind)
        self.setFixedHeight(LANE_HEIGHT)
        self.setObjectName("header")
        self.setCursor(Qt.CursorShape.OpenHandCursor)
        self.setToolTip("click to see the track in the inspector; drag up or down to reorder")
        self._press: QPoint | None = None
        self.setStyleSheet(
            f"#header {{ border-left: 6px solid {kind.colour}; border-bottom: 1px solid #c8c8c4;"
            " background: #f7f7f5; }"
        )
        self.name = QLineEdit(track.name)
        self.name.setToolTip("Track name")
        self.name.editingFinished.connect(self._rename)
        self.remove = QToolButton()
        self.remove.setText("✕")
        self.remove.setToolTip("Remove this track")
        self.remove.clicked.connect(
            lambda: doc.apply("remove track", edits.remove_track, self.track_id)
        )
        self.kind = QLabel(f"{kind.label}\n{kind.display_unit}")
        self.kind.setStyleSheet(f"color: {QColor(kind.colour).darker(140).name()};")
        self.kind.setToolTip(kind.description or kind.label)
        self.gain = QDoubleSpinBox()
        self.gain.setRange(-100.0, 100.0)
        self.gain.setDecimals(2)
        self.gain.setSingleStep(0.05)
        self.gain.setPrefix("gain ")
        self.gain.setMaximumWidth(92)
        self.gain.setKeyboardTracking(False)
        self.gain.valueChanged.connect(self._set_gain)
        self.mute = self._toggle("M", "Mute", "mute")
        self.solo = self._toggle("S", "Solo: play only soloed tracks", "solo")
        top = QHBoxLayout()
        top.addWidget(self.name, 1)
        top.addWidget(self.remove)
        bottom = QHBoxLayout()
        bottom.addWidget(self.kind, 1)
        bottom.addWidget(self.gain)
        bottom.addWidget(self.mute)
        bottom.addWidget(self.solo)
        layout = QVBoxLayout(self)
        layout.setContentsMargins(6, 4, 4, 4)
        layout.setSpacing(2)
        layout.addLayout(top)
        layout.addLayout(bottom)
        for field in (self.name, self.gain):
            field.installEventFilter(self)  # typing in a header shows its track too
        self._shown: Track | None = None
        self.show_track(track)

    def eventFilter(self, watched: QObject, event: QEvent) -> bool:
        if event.type() == QEvent.Type.FocusIn:
            self.doc.select_track(self.track_id)
        return False

    def _toggle(self, text: str, tip: str, field: str) -> QToolButton:
        button = QToolButton()
        button.setText(text)
        button.setToolTip(tip)
        button.setCheckable(True)
        button.clicked.connect(lambda on: self._apply(f"{field} track", **{field: on}))
        return button

    def show_track(self, track: Track) -> None:
        """Show a track's current settings without emitting edits."""
        if track is self._shown and not self.name.hasFocus():
            return  # tracks are immutable: the same object shows the same settings
        self._shown = track
        if not self.name.hasFocus():
            self.name.blockSignals(True)
            quiet.set_text(self.name, track.name)
            self.name.blockSignals(False)
        quiet.show_value(self.gain, track.gain)
        quiet.set_checked(self.mute, track.mute)
        quiet.set_checked(self.solo, track.solo)

    def mousePressEvent(self, event: QMouseEvent) -> None:
        if event.button() == Qt.MouseButton.LeftButton:
            self._press = event.position().toPoint()
            self.doc.select_track(self.track_id)

    def mouseMoveEvent(self, event: QMouseEvent) -> None:
        column = self._column()
        if self._press is None or column is None:
            return
        if (event.position().toPoint() - self._press).manhattanLength() >= DRAG_PX:
            column.reorder_hover(self.track_id, self._column_y(event))

    def mouseReleaseEvent(self, event: QMouseEvent) -> None:
        press, self._press = self._press, None
        column = self._column()
        if press is None or column is None:
            return
        if (event.position().toPoint() - press).manhattanLength() >= DRAG_PX:
            column.reorder_drop(self.track_id, self._column_y(event))

    def _column(self) -> HeaderColumn | None:
        widget = self.parentWidget()
        while widget is not None and not isinstance(widget, HeaderColumn):
            widget = widget.parentWidget()
        return widget

    def _column_y(self, event: QMouseEvent) -> float:
        """The pointer's y among the headers (0 at the first header's top)."""
        return self.y() + event.position().y()

    def _rename(self) -> None:
        track = self.doc.project.track(self.track_id)
        if self.name.text() != track.name:
            self._apply("rename track", name=self.name.text())

    def _set_gain(self, value: float) -> None:
        self._apply("track gain", gain=value)

    def _apply(self, label: str, **fields: Any) -> None:
        """Edit the track from this header; whatever the edit's fate, the next refresh shows
        the track as it then is (a refused edit leaves the widgets showing the old state)."""
        self._shown = None
        self.doc.apply(label, edits.set_track, self.track_id, **fields)


class HeaderColumn(QScrollArea):
    """All track headers, scrolled with the lanes, and an Add track button below them."""

    track_added = Signal(str)

    def __init__(self, doc: Document, first_rows: int | None = None) -> None:
        """With `first_rows`, only that many headers (those a screen shows) are built with the
        column; the others wait for `build_rest` (the window calls it after its first paint)."""
        super().__init__()
        self.doc = doc
        self._first_rows = first_rows
        self._rest: list[Track] = []  # tracks whose headers `build_rest` builds
        self.setFixedWidth(WIDTH)
        self.setWidgetResizable(True)
        self.setHorizontalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAlwaysOff)
        self.setVerticalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAlwaysOff)
        self.setFrameShape(QFrame.Shape.NoFrame)
        inner = QWidget()
        self.rows = QVBoxLayout(inner)
        self.rows.setContentsMargins(0, 0, 0, 0)
        self.rows.setSpacing(0)
        self.add = QPushButton("+ Add track")
        self.add.setToolTip("Add a track of a kind (its meaning: drive, stiffness, damping, ...)")
        self.add.clicked.connect(self._show_kinds)
        self.rows.addWidget(self.add)
        self.rows.addStretch(1)
        self.setWidget(inner)
        self.headers: dict[str, TrackHeader] = {}
        self.drop_line = QFrame(inner)
        self.drop_line.setStyleSheet("background: #3875d7;")
        self.drop_line.hide()
        doc.changed.connect(self.refresh)
        self.refresh()

    def _slot(self, y: float) -> int:
        """The boundary between headers (0 above the first, n below the last) nearest to y."""
        return max(0, min(len(self.headers), round(y / LANE_HEIGHT)))

    def reorder_hover(self, track_id: str, y: float) -> None:
        """Show where a dragged header would go."""
        self.drop_line.setGeometry(0, self._slot(y) * LANE_HEIGHT - 1, self.width(), 3)
        self.drop_line.show()
        self.drop_line.raise_()

    def reorder_drop(self, track_id: str, y: float) -> None:
        """Move the dragged track to where its header was dropped (one undo step)."""
        self.drop_line.hide()
        slot = self._slot(y)
        old = list(self.headers).index(track_id)
        index = slot - 1 if slot > old else slot
        if index != old:
            name = self.doc.project.track(track_id).name
            self.doc.apply(f"move track {name} to place {index + 1}", edits.move_track,
                           track_id, index)  # fmt: skip

    def kind_menu(self) -> QMenu:
        """The menu of track kinds usable on the project's axis."""
        menu = QMenu(self)
        for kind_id, kind in kinds_for_axis(self.doc.project.axis).items():
            action = menu.addAction(f"{kind.label} ({kind.display_unit})")
            action.triggered.connect(lambda _=False, k=kind_id: self.add_track(k))
        return menu

    def _show_kinds(self) -> None:
        self.kind_menu().popup(self.add.mapToGlobal(self.add.rect().bottomLeft()))

    def add_track(self, kind: str) -> str | None:
        """Add a track of a kind (one undo step)."""
        track_id = self.doc.apply("add track", edits.add_track, kind)
        if track_id:
            self.track_added.emit(track_id)
        return track_id

    def refresh(self) -> None:
        """Rebuild headers when tracks come or go; otherwise update them in place."""
        self.build_rest()
        tracks = self.doc.project.tracks
        if [t.id for t in tracks] != list(self.headers):
            for header in self.headers.values():
                header.deleteLater()
            self.headers = {}
            first, self._first_rows = self._first_rows or len(tracks), None  # the first build's
            for track in tracks[:first]:
                self._add_header(track)
            self._rest = list(tracks[first:])
        else:
            for track in tracks:
                self.headers[track.id].show_track(track)  # skips a track it already shows

    def build_rest(self) -> None:
        """Build the headers the column's first build left for later (none if it left none)."""
        rest, self._rest = self._rest, []
        for track in rest:
            self._add_header(track)

    def _add_header(self, track: Track) -> None:
        # made in the column (not moved into it): a header moved in has its style sheet, its
        # fields and their events done again, 3 ms a header
        header = self.headers[track.id] = TrackHeader(self.doc, track, self.widget())
        self.rows.insertWidget(len(self.headers) - 1, header)
