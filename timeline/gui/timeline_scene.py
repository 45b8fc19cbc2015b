"""The timeline scene: lane backgrounds, grid, clip items kept in step with the project."""

from __future__ import annotations

import math

from PySide6.QtCore import QLineF, QRectF
from PySide6.QtGui import QColor, QPainter, QPen
from PySide6.QtWidgets import QGraphicsLineItem, QGraphicsScene

from timeline.kinds import track_kind
from timeline.model import Project
from timeline.placement import overlaps

from .clip_item import ClipItem
from .geometry import Geometry, display_factor, nice_step

LANE_COLOURS = (QColor("#f4f4f2"), QColor("#ebebe8"))
EXTRA_LANE_ROOM = 40


class TimelineScene(QGraphicsScene):
    """Lanes and clips; `sync` updates only what changed, so a drag never rebuilds the scene."""

    def __init__(self, geometry: Geometry) -> None:
        super().__init__()
        self.geometry = geometry
        self.items_by_clip: dict[str, ClipItem] = {}
        self.project: Project | None = None
        self.selection: set[str] = set()
        self.min_width = 800.0
        self.playhead = QGraphicsLineItem()
        self.playhead.setPen(QPen(QColor("#d00000"), 1.5))
        self.playhead.setZValue(20)
        self.cursor = QGraphicsLineItem()
        self.cursor.setPen(QPen(QColor("#2050c0"), 1))
        self.cursor.setZValue(19)
        self.addItem(self.playhead)
        self.addItem(self.cursor)
        self.playhead_u = 0.0
        self.cursor_u = 0.0

    def sync(self, project: Project, selection: list[str]) -> None:
        """Show a project state."""
        self.project, self.selection = project, set(selection)
        seen = set()
        audible = {t.id for t in project.tracks if not t.mute}
        if any(t.solo for t in project.tracks):
            audible = {t.id for t in project.tracks if t.solo}
        for lane, track in enumerate(project.tracks):
            colour = track_kind(track.kind).colour
            covered = overlaps(project, track.id)
            for clip in track.clips:
                item = self.items_by_clip.get(clip.id)
                if item is None:
                    item = self.items_by_clip[clip.id] = ClipItem(self.geometry)
                    self.addItem(item)
                item.update_from(
                    clip,
                    project.tile(clip.tile_id),
                    track.id,
                    lane,
                    colour,
                    project.rate,
                    clip.id in self.selection,
                    track.id not in audible,
                    covered.get(clip.id, ()),
                    project.axis,
                )
                seen.add(clip.id)
        for clip_id in list(self.items_by_clip):
            if clip_id not in seen:
                self.removeItem(self.items_by_clip.pop(clip_id))
        self.refit()

    def refit(self) -> None:
        """Size the scene to the lanes and the project (plus room to drag past the end)."""
        g = self.geometry
        lanes = len(self.project.tracks) if self.project else 0
        width = max(
            self.min_width, g.x((self.project.duration if self.project else 0) * 1.25) + 200
        )
        height = g.lane_top(lanes) + EXTRA_LANE_ROOM
        self.setSceneRect(QRectF(0, 0, width, height))
        self.set_playhead(self.playhead_u)
        self.set_cursor(self.cursor_u)
        self.update()

    def set_playhead(self, u: float) -> None:
        """Move the playhead line."""
        self.playhead_u = u
        x = self.geometry.x(u)
        self.playhead.setLine(QLineF(x, 0, x, self.sceneRect().height()))

    def set_cursor(self, u: float) -> None:
        """Move the edit cursor (where split cuts)."""
        self.cursor_u = u
        x = self.geometry.x(u)
        self.cursor.setLine(QLineF(x, 0, x, self.sceneRect().height()))

    def drawBackground(self, painter: QPainter, rect: QRectF) -> None:
        g = self.geometry
        lanes = len(self.project.tracks) if self.project else 0
        painter.fillRect(rect, QColor("#d9d9d6"))
        for lane in range(lanes):
            band = QRectF(rect.left(), g.lane_top(lane), rect.width(), g.lane_height)
            painter.fillRect(band, LANE_COLOURS[lane % 2])
            painter.setPen(QPen(QColor("#c8c8c4"), 1))
            painter.drawLine(QLineF(rect.left(), band.bottom(), rect.right(), band.bottom()))
        if self.project is None or lanes == 0:
            return
        factor = display_factor(self.project.axis)
        step = nice_step(g.px_per_unit / factor) / factor
        first = math.floor(g.u(rect.left()) / step)
        last = math.ceil(g.u(rect.right()) / step)
        painter.setPen(QPen(QColor(0, 0, 0, 25), 1))
        bottom = g.lane_top(lanes)
        loop = self.project.loop
        if loop is not None:
            band = QRectF(g.x(loop.start), 0, g.x(loop.stop) - g.x(loop.start), bottom)
            painter.fillRect(band.intersected(rect), QColor(56, 160, 90, 30))
        for i in range(first, last + 1):
            x = g.x(i * step)
            painter.drawLine(QLineF(x, 0, x, bottom))

    def grid_step(self) -> float:
        """The grid spacing in axis units at the current zoom (what snapping lands on)."""
        factor = display_factor(self.project.axis if self.project else "time")
        return nice_step(self.geometry.px_per_unit / factor) / factor / 4
