"""The inspector beside the waveform editor: the selected clip, marker or track (whichever was
chosen last; inspector_clip, _marker, _track) above the selected tile's length and a generator's
parameters, with units, typed exactly or scrubbed by dragging their names; each change is one
undo step and is felt at once while playing. A template is never changed: the first edit makes a
copy."""

from __future__ import annotations

import math

from PySide6.QtCore import QPoint, Qt
from PySide6.QtGui import QMouseEvent
from PySide6.QtWidgets import (
    QDoubleSpinBox,
    QFormLayout,
    QFrame,
    QLabel,
    QScrollArea,
    QVBoxLayout,
    QWidget,
)

from timeline.edits import tile_params
from timeline.signal.generators import GENERATORS
from timeline.tiles import GeneratorTile, SampledTile

from . import quiet
from .document import Document
from .geometry import display_factor
from .inspector_clip import ClipPage
from .inspector_marker import MarkerPage
from .inspector_track import TrackPage
from .tile_editing import edit_tile

FREQUENCIES = {"frequency", "f0", "f1", "carrier", "modulation", "bandwidth"}
TIMES = {"attack", "decay", "release"}
SCRUB_STEPS_PER_PX = 1.0  # one spin-box step per pixel dragged (Shift: a tenth)


def param_unit(name: str, axis: str, generator: str = "") -> tuple[float, str]:
    """How a parameter is shown: the factor from stored value to shown value, and the unit."""
    if generator == "emphasis":
        return 1.0, " (0..1)"  # amplitude and frequency are both fractions
    if name in FREQUENCIES:
        return (1.0, " Hz") if axis == "time" else (2 * math.pi, " /turn")
    if name == "phase":
        return (1.0, " periods") if generator == "detents" else (180.0 / math.pi, "°")
    if name in TIMES:
        return (1.0, " s") if axis == "time" else (display_factor(axis), "°")
    return 1.0, ""


class ScrubLabel(QLabel):
    """A parameter's name; drag it left or right to change the value (one undo step)."""

    def __init__(self, text: str, box: QDoubleSpinBox, inspector: Inspector, name: str) -> None:
        super().__init__(text)
        self.box, self.inspector, self.name = box, inspector, name
        self.setCursor(Qt.CursorShape.SizeHorCursor)
        self.setToolTip(f"drag left or right to change {name} (Shift: finer); or type the value")
        self._press: QPoint | None = None
        self._start = 0.0
        self._key: object = None

    def mousePressEvent(self, event: QMouseEvent) -> None:
        if event.button() == Qt.MouseButton.LeftButton:
            self._press = event.position().toPoint()
            self._start = self.box.value()
            self._key = object()

    def mouseMoveEvent(self, event: QMouseEvent) -> None:
        if self._press is None:
            return
        dx = event.position().toPoint().x() - self._press.x()
        fine = 0.1 if event.modifiers() & Qt.KeyboardModifier.ShiftModifier else 1.0
        value = self._start + dx * SCRUB_STEPS_PER_PX * fine * self.box.singleStep()
        self.box.blockSignals(True)
        self.box.setValue(value)
        self.box.blockSignals(False)
        self.inspector.commit(self.name, self.box.value(), self._key)

    def mouseReleaseEvent(self, event: QMouseEvent) -> None:
        self._press = None


class Inspector(QWidget):
    """Shows and edits the document's selected clip, marker or track, and its selected tile."""

    def __init__(self, doc: Document) -> None:
        super().__init__()
        self.doc = doc
        self.pages = {"clip": ClipPage(doc), "marker": MarkerPage(doc), "track": TrackPage(doc)}
        self.rule = QFrame()
        self.rule.setFrameShape(QFrame.Shape.HLine)
        self.title = QLabel()
        self.form = QFormLayout()
        self.form.setContentsMargins(0, 0, 0, 0)
        self.boxes: dict[str, QDoubleSpinBox] = {}
        self.labels: dict[str, ScrubLabel] = {}
        self._shown: tuple[object, ...] = ()
        self._tile_shown: tuple[object, str] = (None, "")  # the tile object shown, and axis
        inner = QWidget()
        layout = QVBoxLayout(inner)
        layout.setContentsMargins(4, 2, 4, 2)
        for page in self.pages.values():
            layout.addWidget(page)
        layout.addWidget(self.rule)
        layout.addWidget(self.title)
        layout.addLayout(self.form)
        layout.addStretch(1)
        self.area = QScrollArea()
        self.area.setWidget(inner)
        self.area.setWidgetResizable(True)
        self.area.setFrameShape(QFrame.Shape.NoFrame)
        self.area.setHorizontalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAlwaysOff)
        outer = QVBoxLayout(self)
        outer.setContentsMargins(0, 0, 0, 0)
        outer.addWidget(self.area)
        self.setMinimumWidth(260)
        doc.changed.connect(lambda _: self.refresh())
        doc.selection_changed.connect(self.refresh)
        self.refresh()

    def shown_page(self) -> str | None:
        """Which page is shown: the last chosen of clip, marker and track, if it still exists."""
        doc = self.doc
        there = {
            "clip": bool(doc.selected_clips),
            "marker": doc.selected_marker is not None,
            "track": doc.selected_track is not None,
        }
        return doc.inspected if there.get(doc.inspected) else None

    def refresh(self) -> None:
        """Show the chosen clip, marker or track; rebuild the tile's fields for another tile, or
        update their values for the same one."""
        shown = self.shown_page()
        for name, page in self.pages.items():
            page.setVisible(name == shown)
        if shown is not None:
            self.pages[shown].refresh()
        self.rule.setVisible(shown is not None)
        self._refresh_tile()

    def _refresh_tile(self) -> None:
        tile_id = self.doc.selected_tile
        tile = self.doc.project.tiles.get(tile_id) if tile_id else None
        axis = self.doc.project.axis
        if tile is not None and self._tile_shown[0] is tile and self._tile_shown[1] == axis:
            return  # tiles are immutable: the same object shows the same fields (a clip drag)
        self._tile_shown = (tile, axis)
        names = [] if tile is None else ["length"]
        if isinstance(tile, GeneratorTile):
            names += [k for k, _ in tile.params]
        shape = (getattr(tile, "generator", type(tile).__name__), axis, tuple(names))
        if shape != self._shown:
            self._rebuild(names, axis, tile)
            self._shown = shape
        if tile is None:
            quiet.set_text(self.title, "Select a tile to see its parameters")
            return
        kind = tile.generator if isinstance(tile, GeneratorTile) else type(tile).__name__
        summary = GENERATORS[tile.generator].summary if isinstance(tile, GeneratorTile) else ""
        quiet.set_text(self.title, f"<b>{tile.name}</b> · {kind}")
        self.title.setToolTip(summary)
        values = {"length": tile.duration, **dict(getattr(tile, "params", ()))}
        for name, box in self.boxes.items():
            quiet.show_value(box, values[name] * self._unit(name, axis, tile)[0])
        self.boxes["length"].setEnabled(not isinstance(tile, SampledTile))

    @staticmethod
    def _unit(name: str, axis: str, tile) -> tuple[float, str]:
        if name == "length":
            return display_factor(axis), (" s" if axis == "time" else "°")
        return param_unit(name, axis, getattr(tile, "generator", ""))

    def _rebuild(self, names: list[str], axis: str, tile) -> None:
        while self.form.rowCount():
            # a field may be the one whose Enter led here: delete it once its signal returns
            row = self.form.takeRow(0)
            for part in (row.labelItem, row.fieldItem):
                if part is not None and (widget := part.widget()) is not None:
                    widget.hide()
                    widget.deleteLater()
        self.boxes, self.labels = {}, {}
        for name in names:
            unit = self._unit(name, axis, tile)[1]
            box = QDoubleSpinBox()
            box.setDecimals(3)
            box.setRange(-1e6, 1e6)
            box.setSuffix(unit)
            box.setKeyboardTracking(False)
            box.setSingleStep(0.01 if name == "length" and axis == "time" else 1.0)
            if name in ("amplitude", "sustain", "depth", "duty", "value", "edge", "width") or (
                getattr(tile, "generator", "") == "emphasis"
            ):
                box.setSingleStep(0.01)
            box.editingFinished.connect(lambda n=name, b=box: self.commit(n, b.value()))
            box.setToolTip(f"{name}{(' in' + unit) if unit else ''}; type a value and press Enter")
            label = ScrubLabel(name, box, self, name)
            self.boxes[name], self.labels[name] = box, label
            self.form.addRow(label, box)

    def commit(self, name: str, shown: float, merge_key: object = None) -> None:
        """Apply a shown value to the tile (a template gets copied first)."""
        tile_id = self.doc.selected_tile
        if tile_id is None:
            return
        self._tile_shown = (None, "")  # shown again after: a refused value goes back to the tile's
        axis = self.doc.project.axis
        tile = self.doc.project.tiles[tile_id]
        value = shown / self._unit(name, axis, tile)[0]
        current = tile.duration if name == "length" else dict(getattr(tile, "params", ())).get(name)
        if current is not None and math.isclose(current, value, rel_tol=1e-12, abs_tol=1e-15):
            return
        edit = tile_params.set_length if name == "length" else tile_params.set_param
        args = (value,) if name == "length" else (name, value)
        edit_tile(self.doc, f"set {name}", tile_id, edit, *args, merge_key=merge_key)
