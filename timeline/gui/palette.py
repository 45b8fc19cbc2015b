"""The tile palette: tabs (Templates, Scratch, user tabs) of tile thumbnails to drag onto tracks.

A tile is renamed in place (F2, or double-click its name); a range dragged from the waveform
editor onto a tab becomes a new tile there, and a tile dragged onto another tab is shown there
too."""

from __future__ import annotations

import math
from pathlib import Path

from PySide6.QtCore import QSize, Qt, Signal
from PySide6.QtGui import QIcon
from PySide6.QtWidgets import (
    QAbstractItemView,
    QFileDialog,
    QHBoxLayout,
    QLineEdit,
    QListView,
    QListWidget,
    QListWidgetItem,
    QPushButton,
    QTabWidget,
    QVBoxLayout,
    QWidget,
)

from timeline import edits
from timeline.edits.naming import unique_tile_name
from timeline.errors import HapticTimelineError
from timeline.files import exporting, importing
from timeline.model import Project
from timeline.tiles import Tile

from .document import Document
from .geometry import axis_text
from .gestures.palette_drop import accept_copy, dropped_tile, tile_mime
from .thumbnails import SIZE, thumbnail

RANGE_MIME = "application/x-haptic-timeline-range"
SCALES = (1.0, 0.9, 0.8, 0.7, 0.6)  # thumbnail sizes tried, largest first, to fit every tile
NAME_ROLE = Qt.ItemDataRole.UserRole + 1  # the tile's name as shown, to tell a rename
LABEL_ROOM = (10, 28)  # grid cell room around a thumbnail for spacing and its name
TILE_FILTERS = {
    "MATLAB (*.mat)": ".mat",
    "Text, Matlab-readable (*.txt)": ".txt",
    "CSV (*.csv)": ".csv",
    "WAV (*.wav)": ".wav",
}


class TileList(QListWidget):
    """One tab's tiles as thumbnails; dragging one carries its tile id; F2 or a double-click
    renames one."""

    range_dropped = Signal(object)
    tile_dropped = Signal(str)  # a tile id dragged here from another tab
    renamed = Signal(str, str)  # tile id, new name

    def __init__(self) -> None:
        super().__init__()
        self.setViewMode(QListView.ViewMode.IconMode)
        self.scale = 1.0
        self._set_scale(1.0)
        self.setResizeMode(QListView.ResizeMode.Adjust)
        self.setMovement(QListView.Movement.Static)
        self.setWordWrap(True)
        self.setDragEnabled(True)
        self.setAcceptDrops(True)
        self.viewport().setAcceptDrops(True)  # drops land on the viewport, not the list
        self.setDragDropMode(QAbstractItemView.DragDropMode.DragDrop)
        self.setDefaultDropAction(Qt.DropAction.CopyAction)
        self.setSelectionMode(QAbstractItemView.SelectionMode.SingleSelection)
        triggers = QAbstractItemView.EditTrigger
        self.setEditTriggers(triggers.EditKeyPressed | triggers.DoubleClicked)
        self.itemChanged.connect(self._changed)

    def _changed(self, item: QListWidgetItem) -> None:
        name = item.text().strip()
        if name and name != item.data(NAME_ROLE):
            self.renamed.emit(item.data(Qt.ItemDataRole.UserRole), name)

    def _set_scale(self, scale: float) -> None:
        self.scale = scale
        icon = QSize(round(SIZE[0] * scale), round(SIZE[1] * scale))
        self.setIconSize(icon)
        self.setGridSize(QSize(icon.width() + LABEL_ROOM[0], icon.height() + LABEL_ROOM[1]))
        self.doItemsLayout()

    def fit_grid(self) -> None:
        """Use the largest thumbnails with which every tile fits without scrolling."""
        scale = next((s for s in SCALES if self._fits(s)), SCALES[-1])  # smallest if none fits
        if scale != self.scale:
            self._set_scale(scale)

    def _fits(self, scale: float) -> bool:
        """Whether every tile shows without scrolling at this thumbnail scale."""
        room = self.contentsRect()
        width = room.width() - self.verticalScrollBar().sizeHint().width()  # as if it showed
        cell_w = round(SIZE[0] * scale) + LABEL_ROOM[0]
        cell_h = round(SIZE[1] * scale) + LABEL_ROOM[1]
        columns = max(1, width // cell_w)
        return math.ceil(self.count() / columns) * cell_h <= room.height()

    def resizeEvent(self, event) -> None:
        super().resizeEvent(event)
        self.fit_grid()

    # Qt takes a null QMimeData (None) as "nothing to drag"; the stubs do not allow it
    def mimeData(self, items):  # noqa: N802  # pyright: ignore[reportIncompatibleMethodOverride]
        return tile_mime(items[0].data(Qt.ItemDataRole.UserRole)) if items else None

    def _wanted(self, mime) -> bool:
        """A range of a tile, or a tile from another tab (one from this tab has its place)."""
        if mime.hasFormat(RANGE_MIME):
            return True
        tile_id = dropped_tile(mime)
        return tile_id is not None and tile_id not in self.tile_ids()

    def tile_ids(self) -> list[str]:
        return [self.item(i).data(Qt.ItemDataRole.UserRole) for i in range(self.count())]

    def dragEnterEvent(self, event) -> None:
        accept_copy(event, self._wanted(event.mimeData()))

    def dragMoveEvent(self, event) -> None:
        self.dragEnterEvent(event)

    def dropEvent(self, event) -> None:
        mime = event.mimeData()
        if not accept_copy(event, self._wanted(mime)):
            return
        if mime.hasFormat(RANGE_MIME):
            self.range_dropped.emit(mime)
        else:
            self.tile_dropped.emit(dropped_tile(mime))


class Palette(QWidget):
    """Tabs of tiles saved with the project; user tabs can be added, renamed and removed."""

    range_dropped = Signal(str, object)  # tab name, mime data

    def __init__(self, doc: Document) -> None:
        super().__init__()
        self.doc = doc
        self.tabs = QTabWidget()
        self.tabs.setDocumentMode(True)
        self.tabs.currentChanged.connect(self._tab_changed)
        self.name = QLineEdit()
        self.name.setPlaceholderText("tab name")
        self.add_button = QPushButton("+ Tab")
        self.add_button.setToolTip("Add a tab (named from the box, or Tab N)")
        self.rename_button = QPushButton("Rename")
        self.rename_button.setToolTip("Rename this tab to the name in the box")
        self.remove_button = QPushButton("− Tab")
        self.remove_button.setToolTip("Remove this tab (its tiles stay in the library)")
        self.add_button.clicked.connect(self.add_tab)
        self.rename_button.clicked.connect(self.rename_tab)
        self.remove_button.clicked.connect(self.remove_tab)
        self.save_button = QPushButton("Save tile…")
        self.save_button.setToolTip("Save the selected tile as .mat, .txt, .csv or .wav")
        self.save_button.clicked.connect(self.save_tile_dialog)
        self.load_button = QPushButton("Load tile…")
        self.load_button.setToolTip("Load a tile from a file into this tab")
        self.load_button.clicked.connect(self.load_tile_dialog)
        tabs_row = QHBoxLayout()
        tabs_row.setContentsMargins(0, 0, 0, 0)
        tabs_row.addWidget(self.name, 1)
        tabs_row.addWidget(self.add_button)
        tabs_row.addWidget(self.rename_button)
        tiles_row = QHBoxLayout()
        tiles_row.setContentsMargins(0, 0, 0, 0)
        tiles_row.addWidget(self.remove_button)
        tiles_row.addStretch(1)
        tiles_row.addWidget(self.save_button)
        tiles_row.addWidget(self.load_button)
        layout = QVBoxLayout(self)
        layout.setContentsMargins(2, 2, 2, 2)
        layout.addWidget(self.tabs, 1)
        layout.addLayout(tabs_row)
        layout.addLayout(tiles_row)
        self._shown: tuple[object, ...] = ()
        self._icons: dict[tuple[str, int], QIcon] = {}
        doc.changed.connect(self.refresh)
        self.refresh()

    def current_tab(self) -> str:
        return self.tabs.tabText(self.tabs.currentIndex())

    def tile_list(self, tab: str) -> TileList:
        for i in range(self.tabs.count()):
            tiles = self.tabs.widget(i)
            if self.tabs.tabText(i) == tab and isinstance(tiles, TileList):
                return tiles
        raise KeyError(tab)

    def refresh(self) -> None:
        """Rebuild the tabs when the palette or its tiles changed."""
        project = self.doc.project
        shown = (project.palette, tuple(id(t) for t in project.tiles.values()), project.axis)
        if shown == self._shown:
            return
        self._shown = shown
        current = self.current_tab()
        self.tabs.blockSignals(True)
        while self.tabs.count():
            widget = self.tabs.widget(0)
            self.tabs.removeTab(0)
            if widget is not None:
                widget.deleteLater()
        for tab in project.palette:
            tiles = TileList()
            tiles.range_dropped.connect(
                lambda mime, name=tab.name: self.range_dropped.emit(name, mime)
            )
            tiles.tile_dropped.connect(lambda tile_id, name=tab.name: self.place(tile_id, name))
            tiles.renamed.connect(self.rename_tile)
            tiles.itemClicked.connect(
                lambda item: self.doc.select_tile(item.data(Qt.ItemDataRole.UserRole))
            )
            for tile_id in tab.tile_ids:
                tile = project.tiles[tile_id]
                item = QListWidgetItem(self._icon(tile), tile.name)
                item.setData(Qt.ItemDataRole.UserRole, tile_id)
                item.setData(NAME_ROLE, tile.name)
                if tab.role != "templates":  # a template keeps its name, as its shape
                    item.setFlags(item.flags() | Qt.ItemFlag.ItemIsEditable)
                length = axis_text(tile.duration, project.axis, ".3g")
                item.setToolTip(f"{tile.name}: {length} (F2 or double-click the name to rename)")
                tiles.addItem(item)
            tiles.fit_grid()
            self.tabs.addTab(tiles, tab.name)
            if tab.name == current:
                self.tabs.setCurrentWidget(tiles)
        self.tabs.blockSignals(False)
        self._tab_changed()

    def _icon(self, tile: Tile) -> QIcon:
        key = (tile.key, id(tile))
        if key not in self._icons:
            self._icons[key] = QIcon(thumbnail(tile, self.doc.project.rate))
        return self._icons[key]

    def _tab_changed(self) -> None:
        role = next((t.role for t in self.doc.project.palette if t.name == self.current_tab()), "")
        self.rename_button.setEnabled(role == "user")
        self.remove_button.setEnabled(role == "user")

    def add_tab(self) -> None:
        """Add a user tab named from the name box (or Tab N)."""
        names = {t.name for t in self.doc.project.palette}
        name = self.name.text().strip() or next(
            f"Tab {i}" for i in range(1, 1000) if f"Tab {i}" not in names
        )
        if self.doc.apply("add palette tab", edits.add_tab, name):
            self.name.clear()
            self.tabs.setCurrentWidget(self.tile_list(name))

    def rename_tab(self) -> None:
        """Rename the current user tab to the text in the name box."""
        old, new = self.current_tab(), self.name.text().strip()
        if self.doc.apply("rename palette tab", edits.rename_tab, old, new):
            self.name.clear()
            self.tabs.setCurrentWidget(self.tile_list(new))

    def rename_tile(self, tile_id: str, name: str) -> None:
        """Rename a tile (one undo step); every clip of it shows the new name."""
        old = self.doc.project.tile(tile_id).name
        if self.doc.apply(f"rename tile {old} to {name}", edits.rename_tile, tile_id, name):
            return
        self._shown = ()  # refused: show the old name again
        self.refresh()

    def place(self, tile_id: str, tab: str) -> None:
        """Show a tile dragged from another tab in this tab too (one undo step)."""
        name = self.doc.project.tile(tile_id).name
        self.doc.apply(f"put {name} in {tab}", edits.place_tile, tile_id, tab)

    def remove_tab(self) -> None:
        """Remove the current user tab (its tiles stay in the library)."""
        self.doc.apply("remove palette tab", edits.remove_tab, self.current_tab())

    def save_tile_dialog(self) -> None:
        """Ask where to save the selected tile, then save it."""
        tile = self.doc.project.tiles.get(self.doc.selected_tile or "")
        if tile is None:
            self.doc.message.emit("select a tile in the palette to save it", "error")
            return
        name, chosen = QFileDialog.getSaveFileName(
            self, "Save tile", tile.name, ";;".join(TILE_FILTERS)
        )
        if name:
            path = Path(name)
            self.save_tile(path if path.suffix else path.with_suffix(TILE_FILTERS.get(chosen, "")))

    def save_tile(self, path: Path) -> bool:
        """Write the selected tile to a file (its format from the extension) at the project rate."""
        tile = self.doc.project.tiles[self.doc.selected_tile]
        try:
            exporting.export_tile(tile, path, rate=self.doc.project.rate)
        except HapticTimelineError as exc:
            self.doc.message.emit(str(exc), "error")
            return False
        self.doc.message.emit(f"saved tile {tile.name} to {path.name}", "info")
        return True

    def load_tile_dialog(self) -> None:
        """Ask for a tile file, then load it into the current tab."""
        name, _ = QFileDialog.getOpenFileName(
            self, "Load tile", "", "Tiles (*.mat *.txt *.csv *.wav *.flac *.ogg *.aiff)"
        )
        if name:
            self.load_tile(Path(name))

    def load_tile(self, path: Path) -> list[str] | None:
        """Read a file's tiles into the current tab (one undo step); returns the new tile ids."""
        tab = self.current_tab()
        try:
            imported = importing.read_file(path)
        except HapticTimelineError as exc:
            self.doc.message.emit(str(exc), "error")
            return None
        tiles = list({id(p.tile): p.tile for p in imported.placements}.values())

        def add_all(project: Project) -> tuple[Project, list[str]]:
            ids = []
            for tile in tiles:
                tile = tile.with_name(unique_tile_name(project, tile.name))
                project, tile_id = edits.add_tile(project, tile, tab)
                ids.append(tile_id)
            return project, ids

        ids = self.doc.apply(f"load tile {path.name}", add_all)
        if ids:
            self.doc.select_tile(ids[-1])
            self.doc.message.emit(f"loaded {path.name} into {tab}", "info")
        return ids
