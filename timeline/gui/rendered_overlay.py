"""View > Show rendered by device: what the device will output, drawn over the designed lanes.

The traces are the ones `haptic-timeline check --plot` draws (timeline.limits.plot.traces: the
drive after the device's clamp and the actuator's response; on a knob, the torque the simulated
motor applies with the player's hand, after clamp and estimator lag and noise; on a position
project, the torque against the knob's angle while the hand turns it through the tables). The
findings worker computes them after each edit, only while the option is on, with their peaks
(trace_peaks.py). Each trace is drawn on every drive lane (the lanes in the unit of the output)
at that lane's scale, as a thin dashed line with one low and one high point per visible pixel
column; hover its label for what it is.
"""

from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING

import numpy as np
from PySide6.QtCore import QRectF, QSettings, Qt
from PySide6.QtGui import QAction, QColor, QFont, QPainter, QPainterPath, QPen
from PySide6.QtWidgets import QGraphicsItem, QGraphicsScene, QGraphicsSimpleTextItem, QMenu

from timeline.model import Project
from timeline.plugins.track_kinds import track_kind

from .geometry import Geometry
from .lane_scale import level_y
from .trace_peaks import Peaks

if TYPE_CHECKING:  # scipy loads with the first rendering, not at start-up
    from timeline.limits.rendered import Trace

SETTING = "view/show_rendered"
COLOURS = (QColor("#1a5fb4"), QColor("#26a269"))  # first trace, second: apart from the lanes' reds
RENDERED_Z = 14  # over the clips, under the findings' shading


class RenderedCurve(QGraphicsItem):
    """One trace's rendering on one lane, labelled at its end (hover the label for what it is).

    It paints only the exposed part of the scene: the trace's peaks (trace_peaks.py, built in
    the findings worker) cut to the visible pixel columns, one low and one high per column, so a
    10-minute design costs the same as a short one at any zoom.
    """

    def __init__(
        self, trace: Trace, peaks: Peaks, lane: int, full: float, g: Geometry, colour: QColor
    ) -> None:
        super().__init__()
        self.trace, self.peaks, self.lane, self.full = trace, peaks, lane, full
        self.g = replace(g)  # the zoom it was made for
        self._pen = QPen(colour, 1.0, Qt.PenStyle.DashLine)  # 1 px: a wider cosmetic pen
        # strokes a dense zig-zag (a zoomed-out buzz) 700x slower
        self._pen.setCosmetic(True)
        self.setZValue(RENDERED_Z)
        self.setAcceptedMouseButtons(Qt.MouseButton.NoButton)
        self.setFlag(QGraphicsItem.GraphicsItemFlag.ItemUsesExtendedStyleOption)
        gap = trace.worst_gap() * trace.scale
        what = "against the knob's angle" if trace.axis == "position" else "over time"
        self.setToolTip(
            f"Rendered by the device (dashed): {trace.label}, {what}, all drive lanes together, "
            "after clamp, actuator response and estimators; the clips show what was designed. "
            f"Largest gap {gap:.3g} {trace.unit}."
        )
        px = g.px_per_unit
        self._rect = QRectF(px * peaks.start, g.lane_top(lane), px * (peaks.stop - peaks.start),
                            g.lane_height)  # fmt: skip
        label = QGraphicsSimpleTextItem(f"- - rendered: {trace.label}", self)
        font = QFont()
        font.setPointSizeF(7.5)
        label.setFont(font)
        label.setBrush(colour)
        label.setToolTip(self.toolTip())
        _, _, highs = self.columns(self._rect.right() - 1.0, self._rect.right())
        end_y = self.y_of(highs[-1]) if highs.size and np.isfinite(highs[-1]) else self._rect.top()
        label.setPos(self._rect.right() + 6, end_y - 12)

    def boundingRect(self) -> QRectF:  # noqa: N802 - Qt's name
        return self._rect

    def pen(self) -> QPen:
        """The dashed pen it draws with."""
        return self._pen

    def shape(self) -> QPainterPath:
        return QPainterPath()  # hover goes to the clips under it; the label has the tooltip

    def y_of(self, value: float) -> float:
        """Scene y of an SI value on this lane."""
        return level_y(self.g, self.lane, value / self.full)

    def columns(self, x_from: float | None = None, x_to: float | None = None):  # noqa: ANN201
        """The pixel columns between scene x `x_from` and `x_to` (default: all): x, lowest and
        highest value (SI)."""
        x_from = self._rect.left() if x_from is None else x_from
        x_to = self._rect.right() if x_to is None else x_to
        return self.peaks.columns(self.g.px_per_unit, x_from, x_to)

    def path(self, x_from: float | None = None, x_to: float | None = None) -> QPainterPath:
        """The polyline through the columns between `x_from` and `x_to` (a gap where nothing)."""
        path, drawing = QPainterPath(), False
        for x, low, high in zip(*self.columns(x_from, x_to), strict=True):
            if not np.isfinite(low):
                drawing = False
                continue
            y_low, y_high = self.y_of(low), self.y_of(high)
            (path.lineTo if drawing else path.moveTo)(float(x), y_low)
            if high != low:
                path.lineTo(float(x), y_high)
            drawing = True
        return path

    def paint(self, painter: QPainter, option, widget=None) -> None:  # noqa: ANN001
        exposed = option.exposedRect
        painter.setPen(self._pen)
        painter.drawPath(self.path(exposed.left() - 2.0, exposed.right() + 2.0))


def drive_lanes(project: Project) -> list[tuple[int, float]]:
    """The lanes the output is drawn on, each with its full scale (SI)."""
    out = []
    for lane, track in enumerate(project.tracks):
        kind = track_kind(track.kind)
        if kind.term == "d":
            out.append(
                (lane, track.full_scale if track.full_scale is not None else kind.full_scale)
            )
    return out


def curves(
    project: Project, traces: list[Trace], peaks: list[Peaks], g: Geometry
) -> list[RenderedCurve]:
    """The items that draw each trace on each drive lane (a knob's torque against its angle on
    a position project)."""
    items = []
    for n, (trace, peak) in enumerate(zip(traces, peaks, strict=True)):
        if trace.time.size == 0 or trace.axis != project.axis:
            continue
        for lane, full in drive_lanes(project):
            items.append(RenderedCurve(trace, peak, lane, full, g, COLOURS[n % len(COLOURS)]))
    return items


def peaks_of(trace: Trace) -> Peaks:
    """The trace's rendered values ready to draw at any zoom (worker thread: numpy only)."""
    if trace.angle is None:
        return Peaks.of(trace.time, trace.rendered, trace.step, uniform=True)
    return Peaks.of(trace.angle, trace.rendered, trace.step, uniform=False)


class RenderedLayer:
    """The curves on the scene and the View menu's switch for them (remembered in QSettings)."""

    def __init__(self, scene: QGraphicsScene) -> None:
        self.scene = scene
        self.items: list[RenderedCurve] = []
        self.shown = bool(QSettings().value(SETTING, False, type=bool))

    def add_action(self, menu: QMenu, toggled) -> QAction:  # noqa: ANN001 - a callable(bool)
        """'Show rendered by device', checkable, in `menu`; `toggled(on)` follows a change."""
        action = menu.addAction("Show &rendered by device")
        action.setCheckable(True)
        action.setChecked(self.shown)
        action.setToolTip("Draw what the device will output (dashed) over the designed lanes")
        action.toggled.connect(lambda on: (self._remember(on), toggled(on)))
        return action

    def _remember(self, on: bool) -> None:
        self.shown = on
        QSettings().setValue(SETTING, on)

    def draw(self, project: Project, traces: list[Trace], peaks: list[Peaks], g: Geometry) -> None:
        """Replace the curves with those of `traces` (none when the option is off)."""
        self.clear()
        if self.shown:
            self.items = curves(project, traces, peaks, g)
            for item in self.items:
                self.scene.addItem(item)

    def clear(self) -> None:
        """Take every curve off the scene."""
        for item in self.items:
            self.scene.removeItem(item)
        self.items = []
