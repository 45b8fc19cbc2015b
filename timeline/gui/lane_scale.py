"""Amplitude scales on the lanes: grid lines at 0, ±½ and ±1 of each track's full scale, labelled
in the track's display unit (mNm, mNm*s/deg, ...) at the left edge of the visible lanes."""

from __future__ import annotations

from PySide6.QtCore import QPointF, QRectF
from PySide6.QtGui import QColor, QFont, QPainter

from timeline.model import Project, Track
from timeline.plugins.track_kinds import track_kind

from .clip_item import value_offset
from .geometry import CLIP_MARGIN, Geometry

LEVELS = (1.0, 0.5, 0.0, -0.5, -1.0)
LABELLED = (1.0, 0.0, -1.0)


def full_scale_text(track: Track, value: float) -> str:
    """A lane value (1.0 = the track's full scale) in the track's display unit."""
    kind = track_kind(track.kind)
    full = track.full_scale if track.full_scale is not None else kind.full_scale
    shown = value * full * kind.display_scale
    return "0" if value == 0 else f"{shown:+.3g} {kind.display_unit}"


def level_y(g: Geometry, lane: int, value: float) -> float:
    """Scene y of a lane value, where the clips draw it."""
    h = g.lane_height - 2 * CLIP_MARGIN
    return g.lane_top(lane) + CLIP_MARGIN + value_offset(value, h)


def visible_lanes(g: Geometry, lanes: int, rect: QRectF) -> range:
    """The lanes (of `lanes`) a scene rectangle crosses."""
    return range(max(0, g.lane_at(rect.top())), min(lanes, g.lane_at(rect.bottom()) + 1))


def draw_grid(painter: QPainter, g: Geometry, project: Project | None, rect: QRectF) -> None:
    """Light horizontal lines at the scale's levels on every lane (under the clips)."""
    if project is None:
        return
    for lane in visible_lanes(g, len(project.tracks), rect):
        for value in LEVELS:
            y = level_y(g, lane, value)
            if rect.top() <= y <= rect.bottom():
                alpha = 45 if value == 0 else 22
                # a pixel-high fill: a blended line across the lanes cost 20x more
                row = QRectF(rect.left(), round(y - 0.5), rect.width(), 1)
                painter.fillRect(row, QColor(0, 0, 0, alpha))


def draw_labels(painter: QPainter, g: Geometry, project: Project | None, visible: QRectF) -> None:
    """The scale's values at the visible left edge of each lane."""
    if project is None:
        return
    font = QFont()
    font.setPointSizeF(7.0)
    painter.setFont(font)
    for lane in visible_lanes(g, len(project.tracks), visible):
        track = project.tracks[lane]
        for value in LABELLED:
            y = level_y(g, lane, value)
            text = full_scale_text(track, value)
            width = painter.fontMetrics().horizontalAdvance(text) + 4
            box = QRectF(visible.left() + 1, y - 6, width, 11)
            painter.fillRect(box, QColor(255, 255, 255, 170))
            painter.setPen(QColor("#555555"))
            painter.drawText(QPointF(box.left() + 2, y + 3), text)
