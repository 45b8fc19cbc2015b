"""Drop a palette tile onto a track: a clip of that tile whose meaning comes from the track."""

from __future__ import annotations

from typing import TYPE_CHECKING

from PySide6.QtCore import QMimeData, QPointF, QRectF, Qt
from PySide6.QtGui import QBrush, QColor, QDropEvent, QPen

from timeline import edits

from ..geometry import CLIP_MARGIN

if TYPE_CHECKING:
    from ..timeline_view import TimelineView

TILE_MIME = "application/x-haptic-timeline-tile"


def tile_mime(tile_id: str) -> QMimeData:
    """Drag data that carries a tile id from the palette."""
    data = QMimeData()
    data.setData(TILE_MIME, tile_id.encode())
    data.setText(tile_id)
    return data


def dropped_tile(mime: QMimeData) -> str | None:
    """The tile id carried by drag data, if any."""
    if mime.hasFormat(TILE_MIME):
        return bytes(mime.data(TILE_MIME).data()).decode()
    return None


def accept_copy(event: QDropEvent, wanted: bool) -> bool:
    """Accept a drag or drop as a copy when it carries what the target wants, else ignore it."""
    if wanted:
        event.setDropAction(Qt.DropAction.CopyAction)
        event.accept()
    else:
        event.ignore()
    return wanted


class PaletteDrop:
    """Shows where the tile would land while dragging over the lanes, and adds the clip on drop."""

    def __init__(self, view: TimelineView, tile_id: str) -> None:
        self.view = view
        self.tile_id = tile_id
        self.duration = view.doc.project.tile(tile_id).duration
        self.ghost = view.scene().addRect(
            QRectF(), QPen(QColor("#333333"), 1, Qt.PenStyle.DashLine), QBrush(QColor(0, 0, 0, 30))
        )
        self.ghost.setZValue(10)

    def where(self, pos: QPointF) -> tuple[str | None, float]:
        """The target track id (None off the lanes) and the snapped start for a scene position."""
        track = self.view.track_at(pos.y())
        start = self.view.snap(max(0.0, self.view.lane_geometry.u(pos.x())), [])
        self.view.snap_line.commit()
        return (track.id if track else None), start

    def hover(self, pos: QPointF) -> bool:
        """Move the ghost; returns whether a drop here would land on a track."""
        track_id, start = self.where(pos)
        g = self.view.lane_geometry
        if track_id is None:
            self.ghost.setRect(QRectF())
            return False
        lane = self.view.lane_of(track_id)
        self.ghost.setRect(
            QRectF(
                g.x(start),
                g.lane_top(lane) + CLIP_MARGIN,
                g.x(self.duration),
                g.lane_height - 2 * CLIP_MARGIN,
            )
        )
        return True

    def drop(self, pos: QPointF) -> str | None:
        """Add the clip; returns its id (None if refused or off the lanes)."""
        self.finish()
        track_id, start = self.where(pos)
        if track_id is None:
            self.view.doc.message.emit("drop the tile on a track", "error")
            return None
        clip_id = self.view.doc.apply("add clip", edits.add_clip, track_id, self.tile_id, start)
        if clip_id:
            self.view.doc.select_clips([clip_id])
            self.view.doc.select_tile(self.tile_id)  # its shape and parameters come up below
        return clip_id

    def finish(self) -> None:
        """Remove the ghost."""
        if self.ghost.scene() is not None:
            self.view.scene().removeItem(self.ghost)
