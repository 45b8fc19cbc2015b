"""The inspector's marker page: the selected marker's name and exact position, edited in place
(no dialog); each change is one undo step."""

from __future__ import annotations

from PySide6.QtWidgets import QFormLayout, QLabel, QLineEdit, QWidget

from timeline.edits import markers
from timeline.model import Project
from timeline.model.markers import Marker

from . import quiet
from .document import Document
from .geometry import axis_text
from .inspector_fields import AXIS_DECIMALS, NumberField, axis_suffix, axis_value, shown_axis


class MarkerPage(QWidget):
    """Name and position of the selected marker."""

    def __init__(self, doc: Document) -> None:
        super().__init__()
        self.doc = doc
        self.title = QLabel("<b>marker</b>")
        self.name = QLineEdit()
        self.name.setToolTip("the marker's name; type and press Enter")
        self.name.editingFinished.connect(self._rename)
        self.position = NumberField(self._move, tip="where the marker is")
        form = QFormLayout(self)
        form.setContentsMargins(0, 0, 0, 0)
        form.addRow(self.title)
        form.addRow("name", self.name)
        form.addRow("position", self.position)

    def marker(self) -> Marker | None:
        index = self.doc.selected_marker
        found = self.doc.project.markers
        return found[index] if index is not None and index < len(found) else None

    def refresh(self) -> None:
        marker = self.marker()
        if marker is None:
            return
        axis = self.doc.project.axis
        if not self.name.hasFocus():
            quiet.set_text(self.name, marker.name)
        quiet.set_format(
            self.position, decimals=AXIS_DECIMALS[axis], suffix=axis_suffix(axis), minimum=0.0
        )
        self.position.show_value(shown_axis(marker.at, axis))

    def _rename(self) -> None:
        marker, name = self.marker(), self.name.text().strip()
        if marker is None or name == marker.name:
            return
        index = self.doc.selected_marker
        self.doc.apply(f"rename marker {marker.name} to {name}", markers.rename_marker, index, name)
        self.refresh()

    def _move(self, shown: float) -> None:
        marker = self.marker()
        if marker is None:
            return
        axis = self.doc.project.axis
        at = axis_value(shown, axis)
        label = f"move marker {marker.name} to {axis_text(at, axis)}"
        index = self.doc.apply(label, move_marker_tracked, self.doc.selected_marker, at)
        if index is not None:
            self.doc.select_marker(index)
        self.refresh()


def move_marker_tracked(project: Project, index: int, at: float) -> tuple[Project, int]:
    """Move a marker; also returns its index among the re-sorted markers (to keep it selected)."""
    name = project.markers[index].name
    project = markers.move_marker(project, index, at)
    return project, project.markers.index(Marker(name, max(0.0, at)))
