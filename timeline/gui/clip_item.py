"""A clip on the timeline: its waveform (peak columns), fades, gain, mirror line and handles."""

from __future__ import annotations

import math
from dataclasses import fields
from functools import cache
from operator import attrgetter

import numpy as np
from PySide6.QtCore import QLineF, QPointF, QRectF, Qt
from PySide6.QtGui import QBrush, QColor, QFont, QPainter, QPen, QPolygonF

from timeline.model import Clip
from timeline.signal.fades import fade_in_gain
from timeline.tiles import Tile

from .clip_shape import clip_columns
from .geometry import CLIP_MARGIN, Geometry, axis_text, gain_text

EDGE_PX = 6.0
HANDLE_PX = 9.0
GAIN_PX = 4.0  # the top edge's strip that drags the clip's gain
GRAB_PX = 10.0  # a clip drawn narrower than this (an emphasis, a tap) is grabbed this wide
SHAPE_LABEL_PX = 60.0  # fades this long show their shape's name
VALUE_RANGE = 1.0  # the lane shows -1 .. 1 of the tile's full scale


def hairline(colour: QColor, style: Qt.PenStyle = Qt.PenStyle.SolidLine) -> QPen:
    """A 1-pixel cosmetic pen: antialiased lines with it cost a tenth of a 1-unit-wide pen's
    (Qt strokes the latter as a path)."""
    pen = QPen(colour, 1, style)
    pen.setCosmetic(True)
    return pen


def value_offset(value: float, height: float) -> float:
    """Distance from a clip's top to where a value (tile units) is drawn, in a clip this high."""
    half = height / 2 - 3
    return height / 2 - max(-1.2, min(1.2, value / VALUE_RANGE)) * half


@cache
def _fade_curve(shape: str) -> tuple[list[float], list[float]]:
    """24 points of a fade-in's gain over [0, 1], as Python floats (for QPointFs)."""
    xs = np.linspace(0.0, 1.0, 24)
    return xs.tolist(), fade_in_gain(xs, shape).tolist()


# every field of a clip but its start, as one tuple (what its wave's columns depend on)
_SHAPE = attrgetter(*(f.name for f in fields(Clip) if f.name != "start"))
WHOLE_WAVE_PX = 4096  # a clip up to this wide keeps its whole wave's columns between paints


class ClipItem:
    """One clip as the timeline shows it: where it is, what a press on it grabs, how it paints.

    Not a QGraphicsItem: the scene's clip layer (timeline_scene.ClipLayer) paints the visible
    clips, so zooming a 20,000-clip project moves no item. Positions are computed from the
    geometry when asked, in scene pixels at the current zoom; `pos`, `mapToScene`,
    `sceneBoundingRect` and friends answer as an item at that place would.
    """

    def __init__(self, geometry: Geometry, clip: Clip, tile: Tile) -> None:
        self.lane_geometry = geometry
        self.clip = clip  # shown once update_from has placed it
        self.tile = tile
        self.colour = QColor("#888888")
        self.rate = 10_000.0
        self.selected = False
        self.track_id = ""
        self.lane = 0
        self.axis = "time"
        self._h = 1.0
        self._key: tuple[object, ...] = ()
        self.muted = False
        self.covered: tuple[tuple[float, float], ...] = ()
        self._wave: tuple[tuple[object, ...], Tile, list[QLineF]] | None = None  # _wave_lines

    def update_from(
        self,
        clip: Clip,
        tile: Tile,
        track_id: str,
        lane: int,
        colour: str,
        rate: float,
        selected: bool,
        muted: bool = False,
        covered: tuple[tuple[float, float], ...] = (),
        axis: str = "time",
    ) -> bool:
        """Show a clip state at a lane; False when nothing changed.

        A muted (or not soloed) track's clips are dimmed; `covered` spans (axis units) where
        another clip overlaps this one are hatched. The zoom is not part of the state: a zoom
        changes no clip.
        """
        h = self.lane_geometry.lane_height - 2 * CLIP_MARGIN
        key = (clip, id(tile), lane, colour, selected, h, rate, muted, covered, axis)
        if key == self._key:
            return False
        self._key = key
        self.clip, self.tile, self.track_id, self.rate = clip, tile, track_id, rate
        self.colour, self.selected, self._h, self.lane = QColor(colour), selected, h, lane
        self.muted, self.covered, self.axis = muted, covered, axis
        return True

    @property
    def _w(self) -> float:
        """Width in pixels at the current zoom (at least 2)."""
        return max(2.0, self.lane_geometry.x(self.clip.duration))

    def pos(self) -> QPointF:
        """Scene position of the clip's top-left corner."""
        g = self.lane_geometry
        return QPointF(g.x(self.clip.start), g.lane_top(self.lane) + CLIP_MARGIN)

    def mapToScene(self, point: QPointF) -> QPointF:  # noqa: N802 - QGraphicsItem's name
        return point + self.pos()

    def mapFromScene(self, point: QPointF) -> QPointF:  # noqa: N802 - QGraphicsItem's name
        return point - self.pos()

    def sceneBoundingRect(self) -> QRectF:  # noqa: N802 - QGraphicsItem's name
        return self.boundingRect().translated(self.pos())

    def opacity(self) -> float:
        """How opaque it is drawn: a muted (or not soloed) track's clips are dimmed."""
        return 0.35 if self.muted else 1.0

    def toolTip(self) -> str:  # noqa: N802 - QGraphicsItem's name
        return clip_tip(self.clip, self.tile, self.muted, self.covered, self.axis)

    # --- geometry and hit zones -----------------------------------------------------------

    def boundingRect(self) -> QRectF:  # noqa: N802 - QGraphicsItem's name
        """Item rectangle, including the grab area of a narrow clip and a pixel of outline."""
        pad = self._pad()
        return QRectF(-1 - pad, -1, self._w + 2 + 2 * pad, self._h + 2)

    def width(self) -> float:
        """The clip's drawn width (its grab area may reach beyond it)."""
        return self._w

    def _pad(self) -> float:
        """How far a narrow clip's grab area reaches beyond each of its ends."""
        return max(0.0, (GRAB_PX - self._w) / 2)

    def _value_ys(self, values: np.ndarray) -> np.ndarray:
        """Item ys of many clip values (value_y on an array)."""
        half = self._h / 2 - 3
        return self._h / 2 - np.clip(values / VALUE_RANGE, -1.2, 1.2) * half

    def value_y(self, value: float) -> float:
        """Item y of a clip value (tile units)."""
        return value_offset(value, self._h)

    def y_value(self, y: float) -> float:
        """Clip value (tile units) at an item y."""
        half = self._h / 2 - 3
        return (self._h / 2 - y) / half * VALUE_RANGE

    def fade_handle(self, which: str) -> QPointF:
        """Where the fade-in or fade-out handle sits (item coordinates)."""
        clip = self.clip
        if which == "in":
            return QPointF(self.lane_geometry.x(clip.fade_in.length), 0.0)
        return QPointF(self._w - self.lane_geometry.x(clip.fade_out.length), 0.0)

    def zone(self, pos: QPointF) -> str:
        """What a press at an item position grabs: fade-in, fade-out, left, right, gain (the top
        edge between the fade handles) or body.

        A clip narrower than GRAB_PX is too small to aim at its edges or fades: it is all body,
        to move (zoom in to trim it)."""
        if self._w < GRAB_PX:
            return "body"
        for which in ("in", "out"):
            h = self.fade_handle(which)
            if abs(pos.x() - h.x()) <= HANDLE_PX and pos.y() <= HANDLE_PX + 2:
                return f"fade-{which}"
        edge = min(EDGE_PX, self._w / 4)
        if pos.x() <= edge:
            return "left"
        if pos.x() >= self._w - edge:
            return "right"
        if pos.y() <= GAIN_PX:
            return "gain"
        return "body"

    # --- painting -------------------------------------------------------------------------

    def paint(self, painter: QPainter, exposed: QRectF) -> None:
        """Draw the clip in item coordinates (the painter translated to `pos`); `exposed` is the
        part to draw, in the same coordinates."""
        clip, w, h = self.clip, self._w, self._h
        fill = QColor(self.colour)
        fill.setAlpha(70 if not self.selected else 110)
        painter.setPen(hairline(self.colour.darker(130)))
        painter.setBrush(QBrush(fill))
        # square corners on whole pixels, not antialiased: a rounded antialiased rectangle
        # took 1.4 ms to fill at this size
        painter.setRenderHint(QPainter.RenderHint.Antialiasing, False)
        painter.drawRect(QRectF(0, 0, w, h))
        painter.setRenderHint(QPainter.RenderHint.Antialiasing, True)
        exposed = exposed.intersected(QRectF(0, 0, w, h))
        self._paint_wave(painter, exposed)
        if w < GRAB_PX:
            self._paint_marker(painter)
        else:
            self._paint_fades(painter)
        if clip.pivot != 0.0 or self.selected:
            painter.setPen(hairline(QColor("#444444"), Qt.PenStyle.DashLine))
            y = self.value_y(clip.pivot)
            painter.drawLine(QPointF(0, y), QPointF(w, y))
        self._paint_label(painter)
        for a, b in self.covered:
            x0, x1 = self.lane_geometry.x(a - clip.start), self.lane_geometry.x(b - clip.start)
            painter.setPen(hairline(QColor("#b02020")))
            painter.setBrush(QBrush(QColor(200, 40, 40, 120), Qt.BrushStyle.BDiagPattern))
            painter.drawRect(QRectF(x0, h - 10, x1 - x0, 10))
        if self.selected:
            painter.setBrush(Qt.BrushStyle.NoBrush)
            painter.setPen(QPen(QColor("#1a1a1a"), 2))
            painter.drawRect(QRectF(1, 1, w - 2, h - 2))

    def _paint_wave(self, painter: QPainter, exposed: QRectF) -> None:
        if exposed.width() <= 0:
            return
        x0, x1 = math.floor(exposed.left()), math.ceil(exposed.right())
        whole = math.ceil(self._w)
        if whole <= WHOLE_WAVE_PX:  # the whole clip's columns, kept, and the exposed ones drawn
            lines = self._wave_lines(0, whole)[max(0, x0) : max(0, x1)]
        else:
            lines = self._wave_lines(x0, x1)
        painter.setPen(hairline(self.colour.darker(150)))
        painter.drawLines(lines)
        painter.setPen(hairline(QColor(0, 0, 0, 60)))
        painter.drawLine(
            QPointF(exposed.left(), self.value_y(0)), QPointF(exposed.right(), self.value_y(0))
        )

    def _wave_lines(self, x0: int, x1: int) -> list[QLineF]:
        """The wave's pixel columns x0..x1 (item coordinates) as vertical lines. The last ones
        drawn are kept: they depend on where the clip sits only through its start, so a clip
        dragged along its lane, and its neighbours repainted around it, reuse them."""
        clip = self.clip
        key = (_SHAPE(clip), self.rate, self._h, self.lane_geometry.px_per_unit, x0, x1)
        if self._wave is not None and self._wave[1] is self.tile and self._wave[0] == key:
            return self._wave[2]
        count = max(1, x1 - x0)
        t0 = clip.start + self.lane_geometry.u(x0)
        t1 = clip.start + self.lane_geometry.u(x1)
        lo, hi = clip_columns(clip, self.tile, self.rate, t0, t1, count)
        # One vertical line per pixel column from its min to its max, each reaching the previous
        # column's range so the trace is continuous: as a filled polygon, a dense hour-long wave
        # took 20-35 ms to paint at some zooms; lines take the same at every zoom.
        top = self._value_ys(np.maximum(hi, np.r_[lo[:1], lo[:-1]]))
        bottom = self._value_ys(np.minimum(lo, np.r_[hi[:1], hi[:-1]]))
        top, bottom = top - 0.5, np.maximum(bottom, top) + 0.5  # at least a pixel: no gaps
        xs = x0 + np.arange(count) + 0.5
        lines = [QLineF(x, a, x, b) for x, a, b in zip(xs.tolist(), top.tolist(), bottom.tolist(),
                                                       strict=True)]  # fmt: skip
        self._wave = (key, self.tile, lines)
        return lines

    def _paint_marker(self, painter: QPainter) -> None:
        """A flag over a narrow clip, as wide as its grab area, so it can be seen and grabbed."""
        pad, w = self._pad(), self._w
        painter.setPen(hairline(self.colour.darker(130)))
        painter.setBrush(QBrush(self.colour))
        painter.drawPolygon(
            QPolygonF([QPointF(-pad, 0), QPointF(w + pad, 0), QPointF(w / 2, GRAB_PX)])
        )

    def _paint_fades(self, painter: QPainter) -> None:
        clip = self.clip
        painter.setPen(hairline(QColor("#202020")))
        for which, fade in (("in", clip.fade_in), ("out", clip.fade_out)):
            length = self.lane_geometry.x(fade.length)
            if length >= 1:
                xs, gain = _fade_curve(fade.shape)
                w, h = self._w, self._h
                points = [
                    QPointF(x * length if which == "in" else w - x * length, h * (1 - g))
                    for x, g in zip(xs, gain, strict=True)
                ]
                painter.setBrush(Qt.BrushStyle.NoBrush)
                painter.drawPolyline(QPolygonF(points))
            handle = self.fade_handle(which)
            painter.setBrush(QBrush(QColor("#ffffff")))
            # inside the clip's rectangle at its ends (what a moved clip repaints): drawn
            # centred there, half of it was left behind on the lane at each move of a drag
            left = min(max(handle.x() - 4, 0.0), self._w - 8)
            painter.drawRect(QRectF(left, 0, 8, 8))
            if length >= SHAPE_LABEL_PX:
                font = QFont()
                font.setPointSizeF(7.0)
                painter.setFont(font)
                x = handle.x() - length if which == "in" else handle.x()
                painter.drawText(
                    QRectF(x, self._h - 14, length, 12), Qt.AlignmentFlag.AlignCenter, fade.shape
                )

    def _paint_label(self, painter: QPainter) -> None:
        clip, tile = self.clip, self.tile
        parts = [tile.name]
        if clip.gain != 1.0:
            parts.append(f"gain {clip.gain:.2g}")
        if clip.scale != 1.0:
            parts.append(f"×{clip.scale:.2g}")
        if clip.stretch != 1.0:
            parts.append(f"stretch {clip.stretch:.2g}")
        if clip.reverse:
            parts.append("reversed")
        font = QFont()
        font.setPointSizeF(8.0)
        painter.setFont(font)
        painter.setPen(QColor("#111111"))
        rect = QRectF(6, 12, max(0.0, self._w - 12), 14)
        text = painter.fontMetrics().elidedText(
            "  ".join(parts), Qt.TextElideMode.ElideRight, int(rect.width())
        )
        if text:
            width = painter.fontMetrics().horizontalAdvance(text) + 6
            painter.fillRect(
                QRectF(rect.left() - 3, rect.top(), width, rect.height()),
                QColor(255, 255, 255, 190),
            )
        painter.drawText(rect, Qt.AlignmentFlag.AlignLeft | Qt.AlignmentFlag.AlignVCenter, text)


def clip_tip(
    clip: Clip, tile: Tile, muted: bool, covered: tuple[tuple[float, float], ...], axis: str
) -> str:
    """The clip's tooltip: tile, where it plays, its gain in dB and x, and what is wrong."""
    lines = [
        f"{tile.name}: {axis_text(clip.start, axis)} to {axis_text(clip.end, axis)}",
        f"gain {gain_text(clip.gain)}",
    ]
    if clip.stretch != 1.0:
        lines.append(f"stretch x{clip.stretch:.3g} ({clip.stretch_mode})")
    if muted:
        lines.append("its track is muted (or another is soloed)")
    if covered:
        lines.append(f"overlaps another clip for {axis_text(sum(b - a for a, b in covered), axis)}")
    lines.append("drag to move, edges to trim, Shift-drag for amplitude, right-click for more")
    return "\n".join(lines)
