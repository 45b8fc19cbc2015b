"""The waveform editor: the selected tile's curve, spline points (or a vibration design's
amplitude or frequency breakpoints) to drag, add and delete, exact values in numeric boxes, and a
range that can be dragged (or sent) to the palette; a palette tile dropped on it opens there."""

from __future__ import annotations

import json
import math

import numpy as np
from PySide6.QtCore import QEvent, QMimeData, QPointF, QRectF, Qt
from PySide6.QtGui import QColor, QDrag, QFont, QKeyEvent, QMouseEvent, QPainter, QPen, QPolygonF
from PySide6.QtWidgets import (
    QComboBox,
    QDoubleSpinBox,
    QHBoxLayout,
    QLabel,
    QPushButton,
    QVBoxLayout,
    QWidget,
)

from timeline.edits import tile_shape
from timeline.model import Track
from timeline.signal.vibration_design import carrier_hz
from timeline.tiles import Tile
from timeline.tiles.vibration_tile import VibrationTile

from . import quiet
from .clip_shape import tile_samples
from .document import Document
from .geometry import axis_text, display_factor
from .gestures.palette_drop import accept_copy, dropped_tile
from .lane_scale import full_scale_text
from .palette import RANGE_MIME
from .tile_editing import edit_tile

PICK_PX = 8.0
ENVELOPE_COLORS = {tile_shape.AMPLITUDE: "#d1495b", tile_shape.FREQUENCY: "#2a9d8f"}
MARGIN = 10.0
DELETE_KEYS = (Qt.Key.Key_Delete, Qt.Key.Key_Backspace)


def range_mime(tile_id: str, a: float, b: float) -> QMimeData:
    """Drag data for a tile range headed to the palette."""
    mime = QMimeData()
    mime.setData(RANGE_MIME, json.dumps([tile_id, a, b]).encode())
    return mime


def read_range(mime: QMimeData) -> tuple[str, float, float]:
    tile_id, a, b = json.loads(bytes(mime.data(RANGE_MIME).data()).decode())
    return tile_id, float(a), float(b)


class Canvas(QWidget):
    """The curve and points: drag a point, double-click to add one, Shift-drag to select a range."""

    def __init__(self, editor: WaveformEditor) -> None:
        super().__init__()
        self.editor = editor
        self.setMinimumHeight(120)
        self.setFocusPolicy(Qt.FocusPolicy.ClickFocus)
        self.dragging: int | None = None
        self.selecting = False
        self.merge_key: object = None
        self.span = (-1.0, 1.0)
        self._drawn: tuple[tuple[object, ...], QPolygonF, float] | None = None  # the curve
        self._tile: Tile | None = None
        self.shown: object = None  # what the last paint showed (refresh skips a repaint of it)

    # mapping between tile units and widget pixels
    def _duration(self) -> float:
        """The shown tile's length (1 while none is shown, e.g. undone during a drag)."""
        tile = self.editor.tile
        return tile.duration if tile is not None else 1.0

    def x_of(self, t: float) -> float:
        return MARGIN + t / self._duration() * (self.width() - 2 * MARGIN)

    def t_of(self, x: float) -> float:
        return (x - MARGIN) / (self.width() - 2 * MARGIN) * self._duration()

    def y_of(self, v: float) -> float:
        lo, hi = self.span
        return MARGIN + (hi - v) / (hi - lo) * (self.height() - 2 * MARGIN)

    def v_of(self, y: float) -> float:
        lo, hi = self.span
        return hi - (y - MARGIN) / (self.height() - 2 * MARGIN) * (hi - lo)

    def point_at(self, pos: QPointF) -> int | None:
        for i, (t, v) in enumerate(self.editor.points() or ()):
            if abs(self.x_of(t) - pos.x()) <= PICK_PX and abs(self.y_of(v) - pos.y()) <= PICK_PX:
                return i
        return None

    def paintEvent(self, event) -> None:
        painter = QPainter(self)
        painter.setRenderHint(QPainter.RenderHint.Antialiasing)
        painter.fillRect(self.rect(), QColor("#ffffff"))
        tile = self.editor.tile
        if tile is None:
            painter.setPen(QColor("#777777"))
            painter.drawText(
                self.rect(),
                Qt.AlignmentFlag.AlignCenter,
                "Select a tile or a clip to edit its shape",
            )
            return
        a, b = self.editor.range
        if b > a:
            painter.fillRect(
                QRectF(self.x_of(a), 0, self.x_of(b) - self.x_of(a), self.height()),
                QColor(56, 117, 215, 45),
            )
        count = max(2, self.width() - int(2 * MARGIN))
        curve, peak = self._curve(tile, count)
        self.span = (-peak * 1.1, peak * 1.1)
        self._paint_scale(painter, peak)
        painter.setPen(QPen(QColor("#3a6ea5"), 1))
        painter.setRenderHint(QPainter.RenderHint.Antialiasing, False)  # columns: no blending
        painter.drawPolyline(curve)
        painter.setRenderHint(QPainter.RenderHint.Antialiasing, True)
        points = self.editor.points() or ()
        if isinstance(tile, VibrationTile):
            self._paint_envelopes(painter, tile)
        for i, (t, v) in enumerate(points):
            chosen = i == self.editor.point
            painter.setBrush(QColor("#d1495b" if chosen else "#ffffff"))
            painter.setPen(QPen(QColor("#222222"), 1))
            painter.drawEllipse(QPointF(self.x_of(t), self.y_of(v)), 5, 5)
        font = QFont()
        font.setPointSizeF(8.0)
        painter.setFont(font)
        painter.setPen(QColor("#444444"))
        painter.drawText(
            QPointF(MARGIN + 2, 12),
            f"{tile.name} · {axis_text(tile.duration, self.editor.doc.project.axis)}",
        )

    def _curve(self, tile: Tile, count: int) -> tuple[QPolygonF, float]:
        """The tile's curve in widget pixels, decimated to `count` columns, and its peak;
        made again only when the tile, the size or the project rate changed."""
        rate = self.editor.doc.project.rate
        key = (id(tile), count, self.height(), rate)  # the tile is held by _drawn's curve key
        if self._drawn is None or self._drawn[0] != key:
            data, _ = tile_samples(tile, rate)
            peak = max(1.0, float(np.abs(data).max()))
            self.span = (-peak * 1.1, peak * 1.1)
            at, values = decimate(data, count)
            xs = MARGIN + at / max(1, len(data) - 1) * (self.width() - 2 * MARGIN)
            lo, hi = self.span
            ys = MARGIN + (hi - values) / (hi - lo) * (self.height() - 2 * MARGIN)
            curve = QPolygonF(
                [QPointF(x, y) for x, y in zip(xs.tolist(), ys.tolist(), strict=True)]
            )
            self._drawn = (key, curve, peak)
            self._tile = tile  # keeps id(tile) from being reused while the key holds it
        return self._drawn[1], self._drawn[2]

    def _paint_envelopes(self, painter: QPainter, tile: VibrationTile) -> None:
        """A design's envelopes over its carrier: the edited one bold, the other faint; in the
        frequency lane, what 0 and 1 mean in Hz."""
        for lane in tile_shape.LANES:
            points = tile_shape.points_of(tile, lane) or ()
            edited = lane == self.editor.lane
            color = QColor(ENVELOPE_COLORS[lane])
            if not edited:
                color.setAlpha(90)
            pen = QPen(color, 1.5 if edited else 1.0)
            if not edited:
                pen.setStyle(Qt.PenStyle.DashLine)
            painter.setPen(pen)
            painter.drawPolyline(
                QPolygonF([QPointF(self.x_of(t), self.y_of(v)) for t, v in points])
            )
        if self.editor.lane == tile_shape.FREQUENCY:
            font = QFont()
            font.setPointSizeF(7.0)
            painter.setFont(font)
            painter.setPen(QColor(ENVELOPE_COLORS[tile_shape.FREQUENCY]))
            for value in (0.0, 1.0):  # just below each line, clear of the name and the scale
                painter.drawText(
                    QPointF(MARGIN + 2, self.y_of(value) + 11), f"{value:g} = {hz_text(value)}"
                )

    def _paint_scale(self, painter: QPainter, peak: float) -> None:
        """Grid lines at 0, ±½ and ±1 of the peak, labelled in tile units and, for the selected
        clip's track, in its display unit (what 1.0 means there)."""
        track = self.editor.track()
        font = QFont()
        font.setPointSizeF(7.0)
        painter.setFont(font)
        top = nice_level(peak)
        for value in (top, top / 2, 0.0, -top / 2, -top):
            y = self.y_of(value)
            painter.setPen(QPen(QColor("#c8c8c8" if value == 0 else "#ececec"), 1))
            painter.drawLine(QPointF(0, y), QPointF(self.width(), y))
            if value in (top, 0.0, -top):
                text = f"{value:+.3g}" if value else "0"
                if track is not None and value:
                    text += f" = {full_scale_text(track, value)} on {track.name}"
                painter.setPen(QColor("#777777"))
                painter.drawText(
                    QPointF(
                        self.width() - MARGIN - 4 - painter.fontMetrics().horizontalAdvance(text),
                        y - 2,
                    ),
                    text,
                )

    def mousePressEvent(self, event: QMouseEvent) -> None:
        if self.editor.tile is None or event.button() != Qt.MouseButton.LeftButton:
            return
        pos = event.position()
        t = self.t_of(pos.x())
        if event.modifiers() & Qt.KeyboardModifier.ShiftModifier:
            self.selecting = True
            self.editor.set_range(t, t)
            return
        index = self.point_at(pos)
        if index is not None:
            self.dragging = index
            self.merge_key = object()
            self.editor.select_point(index)
            return
        a, b = self.editor.range
        if a <= t <= b and b > a and self.editor.tile_id:
            drag = QDrag(self)
            drag.setMimeData(range_mime(self.editor.tile_id, a, b))
            drag.exec(Qt.DropAction.CopyAction)

    def mouseMoveEvent(self, event: QMouseEvent) -> None:
        pos = event.position()
        if self.selecting:
            self.editor.set_range(self.editor.range[0], self.t_of(pos.x()))
        elif self.dragging is not None:
            index = self.editor.apply(
                self.editor.label("move"),
                _move_keep_index,
                self.dragging,
                self.t_of(pos.x()),
                self.v_of(pos.y()),
                self.editor.lane,
                merge_key=self.merge_key,
            )
            if index is not None:
                self.editor.select_point(self.dragging)

    def mouseReleaseEvent(self, event: QMouseEvent) -> None:
        if self.selecting:
            a, b = sorted(self.editor.range)
            self.editor.set_range(max(0.0, a), min(self._duration(), b))
        self.selecting = False
        self.dragging = None

    def mouseDoubleClickEvent(self, event: QMouseEvent) -> None:
        if self.editor.tile is None:
            return
        pos = event.position()
        index = self.editor.apply(
            self.editor.label("add"),
            tile_shape.add_point,
            self.t_of(pos.x()),
            self.v_of(pos.y()),
            self.editor.lane,
        )
        if index is not None:
            self.editor.select_point(index)

    def event(self, event: QEvent) -> bool:
        """Delete and Backspace belong to the focused curve, not to the window's clip Delete."""
        overrides = event.type() == QEvent.Type.ShortcutOverride
        if overrides and isinstance(event, QKeyEvent) and event.key() in DELETE_KEYS:
            event.accept()
            return True
        return super().event(event)

    def keyPressEvent(self, event) -> None:
        if event.key() in DELETE_KEYS:
            self.editor.delete_point()
            event.accept()
            return
        super().keyPressEvent(event)


def decimate(data: np.ndarray, count: int) -> tuple[np.ndarray, np.ndarray]:
    """A polyline through `data` with at most 2 points per column of `count`: each column's
    highest then lowest sample (sample positions, values), so no peak is lost; fewer samples
    than 2 per column are returned as they are."""
    n = len(data)
    if n <= 2 * count:
        return np.arange(n, dtype=np.float64), np.asarray(data, dtype=np.float64)
    starts = (np.arange(count) * n) // count
    hi = np.maximum.reduceat(data, starts)
    lo = np.minimum.reduceat(data, starts)
    middle = starts + (np.r_[starts[1:], n] - starts) / 2
    at = np.repeat(middle, 2)
    values = np.empty(2 * count)
    values[0::2], values[1::2] = hi, lo
    return at, values


def nice_level(peak: float) -> float:
    """The largest 1-2-5 number not above the peak (the scale's top line)."""
    power = 10.0 ** math.floor(math.log10(max(peak, 1e-12)))
    return max(m * power for m in (1.0, 2.0, 5.0) if m * power <= peak * (1 + 1e-12))


def hz_text(frequency: float) -> str:
    """A design's normalised frequency as the carrier it maps to."""
    return f"{float(carrier_hz(frequency)):.1f} Hz"


def _move_keep_index(project, tile_id: str, index: int, t: float, v: float, lane: str):
    return tile_shape.move_point(project, tile_id, index, t, v, lane), index


class WaveformEditor(QWidget):
    """Edits the document's selected tile; numeric boxes hold the selected point's exact values."""

    def __init__(self, doc: Document) -> None:
        super().__init__()
        self.doc = doc
        self.tile_id: str | None = None
        self.point: int | None = None
        self.range = (0.0, 0.0)
        self.lane = tile_shape.AMPLITUDE
        self.canvas = Canvas(self)
        self.lane_box = QComboBox()
        self.lane_box.addItems([lane.capitalize() for lane in tile_shape.LANES])
        self.lane_box.setToolTip("Which envelope of the design the points edit")
        self.lane_box.currentIndexChanged.connect(self.set_lane)
        self.hz_label = QLabel()
        self.hz_label.setMinimumWidth(self.hz_label.fontMetrics().horizontalAdvance("= 230.0 Hz"))
        self.t_box = self._box("t ")
        self.v_box = self._box("value ")
        self.delete_button = QPushButton("Delete point")
        self.delete_button.clicked.connect(self.delete_point)
        self.copy_button = QPushButton("Editable copy")
        self.copy_button.setToolTip("Make a spline tile through points of this shape, in Scratch")
        self.copy_button.clicked.connect(self.editable_copy)
        self.to_palette = QPushButton("Range → palette")
        self.to_palette.setToolTip(
            "Add the Shift-dragged range as a new tile (or drag the range onto a tab)"
        )
        self.to_palette.clicked.connect(lambda: self.range_to_palette("Scratch"))
        # two rows, so the editor fits a 1280-pixel-wide screen
        point_row, tile_row = QHBoxLayout(), QHBoxLayout()
        point_row.addWidget(self.lane_box)
        point_row.addWidget(QLabel("point"))
        point_row.addWidget(self.t_box)
        point_row.addWidget(self.v_box)
        point_row.addWidget(self.hz_label)
        point_row.addStretch(1)
        tile_row.addWidget(self.delete_button)
        tile_row.addStretch(1)
        tile_row.addWidget(self.copy_button)
        tile_row.addWidget(self.to_palette)
        layout = QVBoxLayout(self)
        layout.setContentsMargins(4, 2, 4, 2)
        layout.addWidget(self.canvas, 1)
        layout.addLayout(point_row)
        layout.addLayout(tile_row)
        self.setAcceptDrops(True)
        doc.changed.connect(self.refresh)
        doc.selection_changed.connect(self.refresh)
        self.refresh()

    def _dropped(self, event) -> str | None:
        tile_id = dropped_tile(event.mimeData())
        return tile_id if tile_id in self.doc.project.tiles else None

    def dragEnterEvent(self, event) -> None:
        accept_copy(event, self._dropped(event) is not None)

    def dragMoveEvent(self, event) -> None:
        self.dragEnterEvent(event)

    def dropEvent(self, event) -> None:
        """A palette tile dropped here opens in the editor (the timeline is left as it is)."""
        tile_id = self._dropped(event)
        if not accept_copy(event, tile_id is not None) or tile_id is None:
            return
        self.doc.select_tile(tile_id)
        self.doc.message.emit(f"editing {self.doc.project.tile(tile_id).name}", "info")

    def points(self) -> tuple[tuple[float, float], ...] | None:
        """The shown tile's draggable points (a design's: those of the chosen envelope)."""
        return tile_shape.points_of(self.tile, self.lane)

    def label(self, verb: str) -> str:
        """An undo step's name for a point edit: "move frequency point", "add spline point"."""
        kind = self.lane if isinstance(self.tile, VibrationTile) else "spline"
        return f"{verb} {kind} point"

    def set_lane(self, index: int) -> None:
        """Edit a design's amplitude (0) or frequency (1) envelope."""
        if tile_shape.LANES[index] != self.lane:
            self.lane, self.point = tile_shape.LANES[index], None
            self.lane_box.setCurrentIndex(index)
            self.refresh()

    @property
    def tile(self) -> Tile | None:
        return self.doc.project.tiles.get(self.tile_id) if self.tile_id else None

    def track(self) -> Track | None:
        """The track of the first selected clip that plays this tile (it gives values a unit)."""
        project = self.doc.project
        for clip_id in self.doc.selected_clips:
            track, clip = project.find_clip(clip_id)
            if clip.tile_id == self.tile_id:
                return track
        return None

    def _box(self, prefix: str) -> QDoubleSpinBox:
        box = QDoubleSpinBox()
        box.setPrefix(prefix)
        box.setDecimals(4)
        box.setRange(-1e6, 1e6)
        box.setKeyboardTracking(False)
        box.editingFinished.connect(self._typed)
        return box

    def refresh(self) -> None:
        """Follow the document's selected tile."""
        if self.doc.selected_tile != self.tile_id:
            self.tile_id = self.doc.selected_tile
            self.point, self.range = None, (0.0, 0.0)
        tile = self.tile
        points = self.points()
        if points is not None and self.point is not None and self.point >= len(points):
            self.point = None
        editable = points is not None
        for widget in (self.t_box, self.v_box, self.delete_button):
            widget.setEnabled(editable and self.point is not None)
        self.copy_button.setEnabled(tile is not None)
        self.to_palette.setEnabled(tile is not None and self.range[1] > self.range[0])
        axis = self.doc.project.axis
        quiet.set_format(
            self.t_box,
            prefix="t " if axis == "time" else "θ ",
            suffix=" s" if axis == "time" else "°",
        )
        design = isinstance(tile, VibrationTile)
        self.lane_box.setVisible(design)
        frequency = design and self.lane == tile_shape.FREQUENCY
        self.hz_label.setVisible(frequency)
        quiet.set_format(self.v_box, prefix="f " if frequency else "value ")
        hz = ""
        if editable and self.point is not None:
            t, v = points[self.point]
            hz = f"= {hz_text(v)}"
            quiet.show_value(self.t_box, t * display_factor(axis))
            quiet.show_value(self.v_box, v)
        quiet.set_text(self.hz_label, hz)
        shown = self._shown_key()
        if shown != self.canvas.shown:  # a clip dragged elsewhere changes nothing here
            self.canvas.shown = shown
            self.canvas.update()

    def _shown_key(self) -> tuple[object, ...]:
        """Everything the canvas draws depends on (the tile, points, range, track's scale)."""
        track = self.track()
        scale = None if track is None else (track.id, track.kind, track.full_scale, track.name)
        project = self.doc.project
        tile = self.tile  # by identity: a tile's arrays do not compare with ==
        return (
            id(tile),
            tile,
            self.point,
            self.range,
            self.lane,
            scale,
            project.axis,
            project.rate,
        )

    def select_point(self, index: int | None) -> None:
        self.point = index
        self.refresh()

    def set_range(self, a: float, b: float) -> None:
        self.range = (a, b)
        self.refresh()

    def _typed(self) -> None:
        points = self.points()
        if self.point is None or self.tile_id is None or points is None:
            return
        # a box left as shown keeps the point's exact value (the box rounds it)
        t, v = points[self.point]
        factor = display_factor(self.doc.project.axis)
        if self.t_box.value() != round(t * factor, self.t_box.decimals()):
            t = self.t_box.value() / factor
        if self.v_box.value() != round(v, self.v_box.decimals()):
            v = self.v_box.value()
        if (t, v) == points[self.point]:
            return
        self.apply(self.label("set"), tile_shape.move_point, self.point, t, v, self.lane)

    def apply(self, label: str, edit, *args, merge_key: object = None):
        """Edit the shown tile: edit(project, tile_id, *args), one undo step (see edit_tile)."""
        if self.tile_id is None:
            return None
        return edit_tile(self.doc, label, self.tile_id, edit, *args, merge_key=merge_key)

    def delete_point(self) -> None:
        """Delete the selected control point."""
        if (
            self.point is not None
            and self.tile_id is not None
            and self.apply(self.label("delete"), tile_shape.remove_point, self.point, self.lane)
        ):
            self.select_point(None)

    def editable_copy(self) -> None:
        """Copy the shape into an editable spline tile and edit that."""
        tile_id = self.doc.apply("editable copy", tile_shape.editable_copy, self.tile_id)
        if tile_id:
            self.doc.select_tile(tile_id)

    def range_to_palette(
        self, tab: str, tile_id: str | None = None, a: float | None = None, b: float | None = None
    ) -> str | None:
        """Add the selected range (or the given one) to a palette tab as a new tile."""
        tile_id = tile_id or self.tile_id
        a = self.range[0] if a is None else a
        b = self.range[1] if b is None else b
        return self.doc.apply("range to palette", tile_shape.range_to_palette, tile_id, a, b, tab)
