"""View > Show rendered by device: what the device will output, drawn over the designed lanes.

The traces are the ones `haptic-timeline check --plot` draws (timeline.limits.plot.traces: the
drive after the device's clamp and the actuator's response; on a knob, the torque the simulated
motor applies with the player's hand, after clamp and estimator lag and noise). The findings
worker computes them after each edit, only while the option is on. Each trace is drawn on every
drive lane (the lanes in the unit of the output) at that lane's scale, as a thin dashed line with
one low and one high point per pixel column; hover it for what it is. Time-axis projects only:
a knob's rendering of an angle-axis design is a function of time, not of the angle lanes.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from PySide6.QtCore import QSettings, Qt
from PySide6.QtGui import QAction, QColor, QFont, QPainterPath, QPen
from PySide6.QtWidgets import QGraphicsPathItem, QGraphicsScene, QGraphicsSimpleTextItem, QMenu

from timeline.kinds import track_kind
from timeline.model import Project

from .geometry import Geometry
from .lane_scale import level_y

if TYPE_CHECKING:  # scipy loads with the first rendering, not at start-up
    from timeline.limits.rendered import Trace

SETTING = "view/show_rendered"
COLOURS = (QColor("#1a5fb4"), QColor("#26a269"))  # first trace, second: apart from the lanes' reds
RENDERED_Z = 14  # over the clips, under the findings' shading


class RenderedCurve(QGraphicsPathItem):
    """One trace's rendering on one lane, labelled at its end; `lows`/`highs` are its per-pixel
    extremes (SI)."""

    def __init__(
        self, path: QPainterPath, trace: Trace, lane: int, lows: np.ndarray, highs: np.ndarray,
        colour: QColor,
    ) -> None:  # fmt: skip
        super().__init__(path)
        self.trace, self.lane, self.lows, self.highs = trace, lane, lows, highs
        pen = QPen(colour, 1.3, Qt.PenStyle.DashLine)
        pen.setCosmetic(True)
        self.setPen(pen)
        self.setZValue(RENDERED_Z)
        self.setAcceptedMouseButtons(Qt.MouseButton.NoButton)
        gap = trace.worst_gap() * trace.scale
        tip = (
            f"Rendered by the device (dashed): {trace.label}, all drive lanes together, after "
            "clamp, actuator response and estimators; the clips show what was designed. "
            f"Largest gap {gap:.3g} {trace.unit}."
        )
        self.setToolTip(tip)
        label = QGraphicsSimpleTextItem(f"- - rendered: {trace.label}", self)
        font = QFont()
        font.setPointSizeF(7.5)
        label.setFont(font)
        label.setBrush(colour)
        label.setToolTip(tip)
        end = path.boundingRect()
        label.setPos(end.right() + 6, path.currentPosition().y() - 12)


def extremes(x: np.ndarray, values: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Per pixel column of `x`: the column, the lowest and the highest value in it."""
    columns = np.floor(x).astype(np.int64)
    starts = np.r_[0, np.flatnonzero(np.diff(columns)) + 1]
    return columns[starts], np.minimum.reduceat(values, starts), np.maximum.reduceat(values, starts)


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


def curves(project: Project, traces: list[Trace], g: Geometry) -> list[RenderedCurve]:
    """The items that draw each trace on each drive lane."""
    if project.axis != "time":
        return []
    items = []
    for n, trace in enumerate(traces):
        if trace.time.size == 0:
            continue
        origin = g.x(0.0)
        cols, lows, highs = extremes(origin + (g.x(1.0) - origin) * trace.time, trace.rendered)
        for lane, full in drive_lanes(project):
            path = QPainterPath()
            for i, (col, low, high) in enumerate(zip(cols, lows, highs, strict=True)):
                y_low, y_high = level_y(g, lane, low / full), level_y(g, lane, high / full)
                (path.lineTo if i else path.moveTo)(float(col), y_low)
                if high != low:
                    path.lineTo(float(col), y_high)
            items.append(RenderedCurve(path, trace, lane, lows, highs, COLOURS[n % len(COLOURS)]))
    return items


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

    def draw(self, project: Project, traces: list[Trace], g: Geometry) -> None:
        """Replace the curves with those of `traces` (none when the option is off)."""
        self.clear()
        if self.shown:
            self.items = curves(project, traces, g)
            for item in self.items:
                self.scene.addItem(item)

    def clear(self) -> None:
        """Take every curve off the scene."""
        for item in self.items:
            self.scene.removeItem(item)
        self.items = []
