"""The timeline view: maps mouse presses on clips to gestures, zooms, scrolls and accepts drops."""

from __future__ import annotations

from pathlib import Path

from PySide6.QtCore import QEvent, QObject, QPoint, QPointF, Qt, Signal
from PySide6.QtGui import QDragEnterEvent, QDropEvent, QMouseEvent, QPainter, QWheelEvent
from PySide6.QtWidgets import QGraphicsView, QLabel, QMenu, QWidget

from timeline.edits.vibration import with_emphasis
from timeline.model import Track

from . import lane_scale
from .clip_item import ClipItem
from .document import Document
from .fade_menu import fade_shape_menu
from .geometry import Geometry
from .gestures.amplitude import AmplitudeGesture
from .gestures.base import Gesture
from .gestures.fade import FadeGesture
from .gestures.gain import GainGesture
from .gestures.move import MoveGesture
from .gestures.palette_drop import PaletteDrop, dropped_tile
from .gestures.pivot import PivotGesture, places_mirror_line
from .gestures.rubber_band import RubberBandGesture
from .gestures.select import extended
from .gestures.stretch import StretchGesture
from .gestures.trim import TrimGesture
from .snap_line import SnapLine
from .snapping import EdgeIndex, snap
from .timeline_scene import TimelineScene

SNAP_PX = 8.0
ZOOM_STEP = 1.25
LABELS_PX = 200  # the scale labels at the left edge are within this width
FIT_MARGIN_PX = 12  # room after the project's end when fitted, so the last edge can be grabbed

CURSORS = {
    "left": Qt.CursorShape.SizeHorCursor,
    "right": Qt.CursorShape.SizeHorCursor,
    "fade-in": Qt.CursorShape.PointingHandCursor,
    "fade-out": Qt.CursorShape.PointingHandCursor,
    "body": Qt.CursorShape.OpenHandCursor,
    "gain": Qt.CursorShape.SizeVerCursor,
}


class _NoLayoutRequests(QObject):
    """Drops the layout requests a viewport gets when the drag readout's text changes size.

    The viewport lays nothing out (the readout is placed by hand), but a layout request to it
    makes the scroll area lay out its scroll bars again and repaint them and its frame: on
    every mouse move of a drag whose readout text changed width.
    """

    def eventFilter(self, watched: QObject, event: QEvent) -> bool:  # noqa: N802 - Qt's name
        return event.type() == QEvent.Type.LayoutRequest


class TimelineView(QGraphicsView):
    """Tracks as lanes of clips; every mouse gesture becomes one undoable edit."""

    zoomed = Signal()
    files_dropped = Signal(list, str, float)  # paths, track id, start
    context_requested = Signal(QMenu)  # lets the window fill the clip menu
    gesture_finished = Signal()

    def __init__(self, doc: Document) -> None:
        self.lane_geometry = Geometry()
        self._scene = TimelineScene(self.lane_geometry)
        super().__init__(self._scene)
        self.doc = doc
        self.snapping = True
        self.ripple = False  # Edit > Ripple edit: trims and deletes move the later clips
        self._edges = EdgeIndex()
        self.gesture: Gesture | None = None
        self.drop: PaletteDrop | None = None
        self.menu: QMenu | None = None  # the last context menu shown
        self.menu_at = QPointF()  # the scene point it was asked for at
        # a viewport made in Python, as Qt's own would be: PySide6 knows its type, where one made
        # in C++ makes it look through every widget class (and create their enums, ~20 ms) first
        self.setViewport(QWidget())
        self._no_layout = _NoLayoutRequests(self)
        self.viewport().installEventFilter(self._no_layout)
        self.readout = QLabel(self.viewport())
        self.readout.setStyleSheet(
            "background: rgba(255, 255, 230, 235); border: 1px solid #999; padding: 1px 4px;"
        )
        self.readout.hide()
        self.setAlignment(Qt.AlignmentFlag.AlignLeft | Qt.AlignmentFlag.AlignTop)
        self.setRenderHint(QPainter.RenderHint.Antialiasing)
        self.setViewportUpdateMode(QGraphicsView.ViewportUpdateMode.MinimalViewportUpdate)
        self.snap_line = SnapLine(self._scene, self.lane_geometry)
        self.setAcceptDrops(True)
        self.setMouseTracking(True)
        self.setHorizontalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAlwaysOn)
        doc.changed.connect(self.refresh)
        doc.selection_changed.connect(self.refresh)
        self.refresh()

    def scene(self) -> TimelineScene:  # type: ignore[override]
        return self._scene

    # --- model -> view ---------------------------------------------------------------------

    def refresh(self) -> None:
        """Redraw from the document; a selected design's emphasis clips are drawn selected too,
        since moving, copying and deleting it takes them along."""
        self.scene().min_width = self.viewport().width()
        project = self.doc.project
        self.scene().sync(project, with_emphasis(project, self.doc.selected_clips))

    def clip_items(self) -> list[ClipItem]:
        return list(self.scene().items_by_clip.values())

    def clip_item(self, clip_id: str) -> ClipItem:
        return self.scene().items_by_clip[clip_id]

    def track_at(self, y: float) -> Track | None:
        """The track whose lane is at scene y, or None."""
        lane = self.lane_geometry.lane_at(y)
        tracks = self.doc.project.tracks
        return tracks[lane] if 0 <= lane < len(tracks) else None

    def lane_of(self, track_id: str) -> int:
        return [t.id for t in self.doc.project.tracks].index(track_id)

    def clip_scene_rect(self, clip_id: str):
        """A clip's rectangle in scene coordinates (what tests and drops aim at)."""
        return self.clip_item(clip_id).sceneBoundingRect().adjusted(1, 1, -1, -1)

    def snap(self, u: float, dragged: list[str]) -> float:
        """Snap an axis position to clip edges or the grid, if snapping is on; the snap line
        is placed where it snapped (shown when the gesture's move commits it)."""
        if not self.snapping:
            return u
        nearest = self._edges.nearest(self.doc.project, u, dragged)
        snapped = snap(u, [nearest], self.scene().grid_step(), self.lane_geometry.u(SNAP_PX))
        self.snap_line.place(snapped if snapped != u else None)
        return snapped

    # --- zoom and scroll -------------------------------------------------------------------

    def zoom(self, factor: float, anchor_x: float | None = None) -> None:
        """Zoom the time (or angle) axis about a viewport x (the centre by default)."""
        if anchor_x is None:
            anchor_x = self.viewport().width() / 2
        u = self.lane_geometry.u(self.mapToScene(int(anchor_x), 0).x())
        self.lane_geometry.zoomed(factor)
        self.refresh()
        self.horizontalScrollBar().setValue(int(self.lane_geometry.x(u) - anchor_x))
        self.zoomed.emit()

    def fit(self) -> None:
        """Zoom so the whole project fits the width."""
        duration = self.doc.project.duration or 1.0
        width = max(100, self.viewport().width() - FIT_MARGIN_PX)
        self.lane_geometry.px_per_unit = width / duration
        self.refresh()
        self.horizontalScrollBar().setValue(0)
        self.zoomed.emit()

    def keep_visible(self, u: float) -> None:
        """Page the view so an axis position (the playing playhead) stays on screen."""
        bar = self.horizontalScrollBar()
        x, width = self.lane_geometry.x(u), self.viewport().width()
        if not bar.value() <= x <= bar.value() + width:
            bar.setValue(int(x - 0.1 * width))

    def drawBackground(self, painter: QPainter, rect) -> None:
        painter.save()
        painter.setRenderHint(QPainter.RenderHint.Antialiasing, False)  # level lines on pixels
        super().drawBackground(painter, rect)
        lane_scale.draw_grid(painter, self.lane_geometry, self.doc.project, rect)
        painter.restore()

    def drawForeground(self, painter: QPainter, rect) -> None:
        visible = self.mapToScene(self.viewport().rect()).boundingRect()
        if rect.left() <= visible.left() + LABELS_PX:  # a clip repainted elsewhere: no labels
            lane_scale.draw_labels(painter, self.lane_geometry, self.doc.project, visible)

    def scrollContentsBy(self, dx: int, dy: int) -> None:
        super().scrollContentsBy(dx, dy)
        if dx:
            self.viewport().update()  # the scale labels stay at the left edge
        self.zoomed.emit()

    def wheelEvent(self, event: QWheelEvent) -> None:
        if event.modifiers() & Qt.KeyboardModifier.ControlModifier:
            steps = event.angleDelta().y() / 120
            self.zoom(ZOOM_STEP**steps, event.position().x())
            event.accept()
            return
        if event.modifiers() & Qt.KeyboardModifier.ShiftModifier:
            bar = self.horizontalScrollBar()
            bar.setValue(bar.value() - event.angleDelta().y())
            event.accept()
            return
        super().wheelEvent(event)

    # --- mouse -----------------------------------------------------------------------------

    def show_readout(self, text: str, scene_pos: QPointF) -> None:
        """A small label of numbers beside the mouse during a drag (time, length, gain, ...)."""
        self.readout.setText(text)
        self.readout.adjustSize()
        at = self.mapFromScene(scene_pos) + QPoint(14, 14)
        room = self.viewport().width() - self.readout.width() - 2
        self.readout.move(min(at.x(), max(0, room)), at.y())
        self.readout.show()

    def item_at(self, pos: QPointF) -> ClipItem | None:
        """The clip under a viewport position (within a narrow clip's grab area; where two clips
        touch, the one the pointer is over)."""
        return self.scene().clip_at(self.mapToScene(pos.toPoint()))

    def mousePressEvent(self, event: QMouseEvent) -> None:
        if event.button() != Qt.MouseButton.LeftButton:
            super().mousePressEvent(event)
            return
        pos = self.mapToScene(event.position().toPoint())
        mods = event.modifiers()
        item = self.item_at(event.position())
        self.scene().set_cursor(max(0.0, self.lane_geometry.u(pos.x())))
        if item is None:
            add = bool(mods & Qt.KeyboardModifier.ControlModifier)
            self.gesture = RubberBandGesture(self, pos, add)
            return
        clip_id = item.clip.id
        if mods & Qt.KeyboardModifier.ControlModifier and not places_mirror_line(mods):
            chosen = list(self.doc.selected_clips)
            chosen.remove(clip_id) if clip_id in chosen else chosen.append(clip_id)
            self.doc.select_clips(chosen)
            return
        if mods & Qt.KeyboardModifier.ShiftModifier and clip_id not in self.doc.selected_clips:
            self.doc.select_clips(extended(self.doc.project, self.doc.selected_clips, clip_id))
        elif clip_id not in self.doc.selected_clips:
            self.doc.select_clips([clip_id])
        else:  # the pressed clip first: the inspector shows it and Shift+click extends from it
            self.doc.select_clips([clip_id, *self.doc.selected_clips])
        self.doc.select_tile(item.clip.tile_id)
        self.gesture = self._gesture_for(item, pos, mods)

    def _gesture_for(self, item: ClipItem, pos: QPointF, mods) -> Gesture:
        zone = item.zone(item.mapFromScene(pos))
        clip_id = item.clip.id
        shift = bool(mods & Qt.KeyboardModifier.ShiftModifier)
        if places_mirror_line(mods):
            return PivotGesture(self, pos, clip_id)
        if zone.startswith("fade-"):
            return FadeGesture(self, pos, clip_id, zone[5:])
        if zone == "gain":
            return GainGesture(self, pos, clip_id)
        if zone in ("left", "right"):
            cls = StretchGesture if shift else TrimGesture
            return cls(self, pos, clip_id, zone)
        if shift:
            return AmplitudeGesture(self, pos, clip_id)
        return MoveGesture(self, pos, clip_id)

    def mouseMoveEvent(self, event: QMouseEvent) -> None:
        pos = self.mapToScene(event.position().toPoint())
        if self.gesture is not None:
            self.gesture.move(pos)
            return
        item = self.item_at(event.position())
        if item is None:
            self.viewport().unsetCursor()
        else:
            self.viewport().setCursor(CURSORS[item.zone(item.mapFromScene(pos))])
        super().mouseMoveEvent(event)

    def mouseReleaseEvent(self, event: QMouseEvent) -> None:
        if self.gesture is None:
            super().mouseReleaseEvent(event)
            return
        gesture, self.gesture = self.gesture, None
        gesture.release(self.mapToScene(event.position().toPoint()))
        self.readout.hide()
        self.snap_line.show_at(None)
        self.gesture_finished.emit()

    def contextMenuEvent(self, event) -> None:
        self.menu_at = self.mapToScene(event.pos())  # where "Set mirror line here" puts it
        item = self.item_at(QPointF(event.pos()))
        if item is not None:
            zone = item.zone(item.mapFromScene(self.mapToScene(event.pos())))
            if zone.startswith("fade-"):
                self.menu = fade_shape_menu(self.doc, item.clip.id, zone[5:], self)
                self.menu.popup(event.globalPos())
                return
        if item is not None and item.clip.id not in self.doc.selected_clips:
            self.doc.select_clips([item.clip.id])
        if item is not None:
            self.scene().set_cursor(self.lane_geometry.u(self.mapToScene(event.pos()).x()))
        menu = self.menu = QMenu(self)
        self.context_requested.emit(menu)
        if not menu.isEmpty():
            menu.popup(event.globalPos())

    # --- drops: palette tiles and files ----------------------------------------------------

    def dragEnterEvent(self, event: QDragEnterEvent) -> None:
        tile_id = dropped_tile(event.mimeData())
        if tile_id is not None and tile_id in self.doc.project.tiles:
            self.drop = PaletteDrop(self, tile_id)
            event.acceptProposedAction()
        elif event.mimeData().hasUrls():
            event.acceptProposedAction()
        else:
            event.ignore()

    def dragMoveEvent(self, event) -> None:
        pos = self.mapToScene(event.position().toPoint())
        if self.drop is not None:
            self.drop.hover(pos)
        event.acceptProposedAction()

    def dragLeaveEvent(self, event) -> None:
        self.snap_line.show_at(None)
        if self.drop is not None:
            self.drop.finish()
            self.drop = None

    def dropEvent(self, event: QDropEvent) -> None:
        pos = self.mapToScene(event.position().toPoint())
        self.snap_line.show_at(None)
        if self.drop is not None:
            drop, self.drop = self.drop, None
            drop.drop(pos)
            event.acceptProposedAction()
            return
        paths = [u.toLocalFile() for u in event.mimeData().urls() if u.isLocalFile()]
        track = self.track_at(pos.y())
        if paths:
            self.files_dropped.emit(
                [Path(p) for p in paths],
                track.id if track else "",
                max(0.0, self.lane_geometry.u(pos.x())),
            )
            event.acceptProposedAction()
