"""The ruler above the lanes: seconds, or degrees in position mode, with markers and the loop.

Click to place the playhead and cursor; drag to set the loop region (REAPER's ruler drag); drag
the playhead to scrub (the Scrubber, when given one, plays what is under it); click a marker's
flag to show it in the inspector, drag it to move it, double-click it to rename it in place;
right-click a marker to rename or delete it, or the loop to clear it.
"""

from __future__ import annotations

import math
from collections.abc import Callable

from PySide6.QtCore import QPointF, QRectF, Qt, Signal
from PySide6.QtGui import QColor, QFont, QMouseEvent, QPainter, QPen, QPolygonF
from PySide6.QtWidgets import QLineEdit, QMenu, QWidget

from timeline.edits import markers
from timeline.model import Project

from .geometry import axis_text, display_factor, display_unit, format_tick, nice_step
from .scrub import Scrubber
from .timeline_view import TimelineView

HEIGHT = 40
TICKS_TOP = 20  # marker flags and the loop band above, ticks and labels below
FLAG_PX = 6.0
PLAYHEAD_GRAB_PX = 5.0  # a press this near the playhead (below the flags) scrubs it
LOOP_COLOUR = QColor(56, 160, 90, 70)
MARKER_COLOUR = QColor("#c07000")


class Ruler(QWidget):
    """Tick marks and labels that follow the view's zoom and scroll; markers and loop region."""

    clicked = Signal(float)  # axis position the playhead and cursor moved to
    loop_dragged = Signal()
    scrubbed = Signal(float)  # where a scrub of the playhead was let go

    def __init__(self, view: TimelineView) -> None:
        super().__init__()
        self.view = view
        self.doc = view.doc
        self.setFixedHeight(HEIGHT)
        self.setMouseTracking(True)
        self.ask_name: Callable[[str], str | None] = self._ask_name
        self.name_edit: QLineEdit | None = None  # the in-place rename box, while open
        self._renaming: int | None = None
        self._press: float | None = None  # x where the left button went down
        self._marker: int | None = None  # index of the marker being dragged
        self._scrub = False  # the press was on the playhead: a drag scrubs it
        self._scrubbing = False  # the playhead has moved under the mouse since the press
        self.scrubber: Scrubber | None = None  # plays what is under a scrubbed playhead
        self._key: object = None
        self._base = None
        self._shows = self._shown_of(self.doc.project)  # what it shows of the project
        view.zoomed.connect(self.update)
        self.doc.changed.connect(self._project_changed)

    def _project_changed(self, project: Project) -> None:
        """Repaint when the axis, loop region or markers changed, not when a clip moved."""
        shows = self._shown_of(project)
        if shows != self._shows:
            self._shows = shows
            self.update()

    @staticmethod
    def _shown_of(project: Project) -> tuple[object, ...]:
        return (project.axis, project.loop, project.markers)

    # --- mapping ---------------------------------------------------------------------------

    def x_of(self, u: float) -> float:
        return self.view.lane_geometry.x(u) - self.view.horizontalScrollBar().value()

    def u_of(self, x: float) -> float:
        return max(0.0, self.view.lane_geometry.u(x + self.view.horizontalScrollBar().value()))

    def marker_at(self, x: float, y: float) -> int | None:
        """The marker whose flag is under a widget point."""
        if y > TICKS_TOP:
            return None
        for i, m in enumerate(self.doc.project.markers):
            if abs(self.x_of(m.at) - x) <= FLAG_PX:
                return i
        return None

    # --- painting --------------------------------------------------------------------------

    def paintEvent(self, event) -> None:
        painter = QPainter(self)
        painter.fillRect(self.rect(), QColor("#fafaf8"))
        project = self.doc.project
        axis = project.axis
        g = self.view.lane_geometry
        factor = display_factor(axis)
        step = nice_step(g.px_per_unit / factor)
        left = self.view.horizontalScrollBar().value()
        first = math.floor(g.u(left) * factor / step)
        last = math.ceil(g.u(left + self.width()) * factor / step)
        font = QFont()
        font.setPointSizeF(8.0)
        painter.setFont(font)
        if project.loop is not None:
            a, b = self.x_of(project.loop.start), self.x_of(project.loop.stop)
            painter.fillRect(QRectF(a, 0, b - a, HEIGHT), LOOP_COLOUR)
        for i in range(first, last + 1):
            x = g.x(i * step / factor) - left
            painter.setPen(QPen(QColor("#555555"), 1))
            painter.drawLine(QPointF(x, HEIGHT - 9), QPointF(x, HEIGHT))
            painter.drawText(
                QPointF(x + 3, HEIGHT - 10), format_tick(i * step, step) + display_unit(axis)
            )
            for sub in range(1, 4):
                xs = x + g.x(step / factor) * sub / 4
                painter.setPen(QPen(QColor("#aaaaaa"), 1))
                painter.drawLine(QPointF(xs, HEIGHT - 4), QPointF(xs, HEIGHT))
        painter.setPen(QPen(QColor("#bbbbbb"), 1))
        painter.drawLine(0, HEIGHT - 1, self.width(), HEIGHT - 1)
        for m in project.markers:
            x = self.x_of(m.at)
            painter.setPen(QPen(MARKER_COLOUR, 1))
            painter.setBrush(MARKER_COLOUR)
            painter.drawPolygon(QPolygonF([QPointF(x, 2), QPointF(x + FLAG_PX, 7), QPointF(x, 12)]))
            painter.drawLine(QPointF(x, 2), QPointF(x, HEIGHT))
            painter.drawText(QPointF(x + FLAG_PX + 2, 12), m.name)
        x = self.x_of(self.view.scene().playhead_u)
        painter.setPen(QPen(QColor("#d00000"), 2))
        painter.drawLine(QPointF(x, 0), QPointF(x, HEIGHT))

    # --- mouse -----------------------------------------------------------------------------

    def mousePressEvent(self, event: QMouseEvent) -> None:
        if event.button() != Qt.MouseButton.LeftButton:
            return
        pos = event.position()
        self._press = pos.x()
        self._marker = self.marker_at(pos.x(), pos.y())
        playhead = self.x_of(self.view.scene().playhead_u)
        self._scrub = self._marker is None and abs(pos.x() - playhead) <= PLAYHEAD_GRAB_PX
        self._key, self._base = object(), self.doc.project
        if self._marker is not None:
            self.doc.select_marker(self._marker)

    def mouseMoveEvent(self, event: QMouseEvent) -> None:
        pos = event.position()
        if self._press is None:
            i = self.marker_at(pos.x(), pos.y())
            self.setToolTip(self._tip(i, pos.x()))
            return
        if abs(pos.x() - self._press) < 3 and not self._scrubbing:
            return
        u0, u = self.u_of(self._press), self.u_of(pos.x())
        if self._scrub:
            if self.scrubber is not None and not self._scrubbing:
                self.scrubber.begin()
            self._scrubbing = True
            self.place(u)  # the playhead, the cursor and the readout follow
            if self.scrubber is not None:
                self.scrubber.move(u)
            return
        if self._marker is not None:
            from .inspector_marker import move_marker_tracked  # the marker panel's, loaded later

            index = self.doc.apply(
                "move marker", move_marker_tracked, self._marker, u,
                base=self._base, merge_key=self._key,
            )  # fmt: skip
            if index is not None:
                self.doc.select_marker(index)
            self.doc.message.emit(f"marker at {axis_text(u, self.doc.project.axis)}", "info")
        else:
            self.doc.apply(
                "loop region", markers.set_loop, u0, u, base=self._base, merge_key=self._key
            )
            loop = self.doc.project.loop
            if loop is not None:
                axis = self.doc.project.axis
                length = axis_text(loop.stop - loop.start, axis)
                self.doc.message.emit(
                    f"loop {axis_text(loop.start, axis)} to {axis_text(loop.stop, axis)}"
                    f" ({length})",
                    "info",
                )
            self.loop_dragged.emit()

    def mouseReleaseEvent(self, event: QMouseEvent) -> None:
        if event.button() != Qt.MouseButton.LeftButton or self._press is None:
            return
        press, self._press = self._press, None
        if self._scrubbing:
            self._scrub = self._scrubbing = False
            u = self.u_of(event.position().x())
            self.place(u)
            if self.scrubber is not None:
                self.scrubber.end()
            self.scrubbed.emit(u)
            return
        if abs(event.position().x() - press) >= 3:
            return
        u = self.u_of(event.position().x())
        if self._marker is not None:
            u = self.doc.project.markers[self._marker].at
        self.place(u)

    def place(self, u: float) -> None:
        """Move the playhead and the edit cursor to an axis position."""
        self.view.scene().set_cursor(u)
        self.view.scene().set_playhead(u)
        self.update()
        self.clicked.emit(u)

    def mouseDoubleClickEvent(self, event: QMouseEvent) -> None:
        i = self.marker_at(event.position().x(), event.position().y())
        if i is not None:
            self.rename(i)

    def contextMenuEvent(self, event) -> None:
        menu = self.menu_at(event.pos().x(), event.pos().y())
        if not menu.isEmpty():
            menu.popup(event.globalPos())

    def menu_at(self, x: float, y: float) -> QMenu:
        """The right-click menu for a ruler point: the marker there, and the loop region."""
        menu = QMenu(self)
        i = self.marker_at(x, y)
        if i is not None:
            name = self.doc.project.markers[i].name
            menu.addAction(f"Rename marker {name}", lambda: self.rename(i))
            menu.addAction(
                f"Delete marker {name}",
                lambda: self.doc.apply("delete marker", markers.remove_marker, i),
            )
        if self.doc.project.loop is not None:
            menu.addAction(
                "Clear loop region", lambda: self.doc.apply("clear loop", markers.set_loop, None)
            )
        return menu

    def rename(self, index: int) -> None:
        """Rename a marker: in place, in a box over its flag (Enter applies it, one undo step;
        Escape or clicking elsewhere leaves it)."""
        self._renaming = index
        self.doc.select_marker(index)
        name = self.ask_name(self.doc.project.markers[index].name)
        if name:
            self._apply_name(index, name)

    def _apply_name(self, index: int, name: str) -> None:
        old = self.doc.project.markers[index].name
        if name.strip() and name.strip() != old:
            self.doc.apply(f"rename marker {old} to {name.strip()}", markers.rename_marker,
                           index, name)  # fmt: skip

    def _ask_name(self, current: str) -> str | None:
        """Open the in-place box over the flag; it applies the name itself on Enter."""
        index = self._renaming
        if index is None:
            return None
        self._close_name_edit()
        box = self.name_edit = QLineEdit(current, self)
        box.selectAll()
        box.setToolTip("the marker's name: Enter renames it, Escape leaves it")
        box.move(int(self.x_of(self.doc.project.markers[index].at) + FLAG_PX + 1), 0)
        box.resize(max(80, box.sizeHint().width()), TICKS_TOP)
        box.returnPressed.connect(lambda: self._finish_name(index))
        box.editingFinished.connect(self._close_name_edit)
        box.show()
        box.setFocus()
        return None

    def _finish_name(self, index: int) -> None:
        box = self.name_edit
        if box is not None and index < len(self.doc.project.markers):
            self._apply_name(index, box.text())
        self._close_name_edit()

    def _close_name_edit(self) -> None:
        box, self.name_edit = self.name_edit, None
        if box is not None:
            box.hide()
            box.deleteLater()

    def keyPressEvent(self, event) -> None:
        if event.key() == Qt.Key.Key_Escape:
            self._close_name_edit()
            return
        super().keyPressEvent(event)

    def _tip(self, index: int | None, x: float) -> str:
        axis = self.doc.project.axis
        if index is not None:
            m = self.doc.project.markers[index]
            return (
                f"marker {m.name} at {axis_text(m.at, axis)}: drag to move, "
                "double-click to rename, right-click to delete"
            )
        if abs(x - self.x_of(self.view.scene().playhead_u)) <= PLAYHEAD_GRAB_PX:
            return (
                "the playhead: drag it to scrub, feeling what is under it "
                "(playing goes on from where you let go)"
            )
        return (
            f"{axis_text(self.u_of(x), axis)}: click to move the playhead, "
            "drag to set the loop region"
        )
