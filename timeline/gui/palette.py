"""The tile palette: tabs (Templates, Scratch, user tabs) of tile thumbnails to drag onto tracks."""

from __future__ import annotations

from PySide6.QtCore import QSize, Qt, Signal
from PySide6.QtGui import QIcon
from PySide6.QtWidgets import (
    QAbstractItemView,
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
from timeline.tiles import Tile

from .document import Document
from .gestures.palette_drop import tile_mime
from .thumbnails import SIZE, thumbnail

RANGE_MIME = "application/x-haptic-timeline-range"


class TileList(QListWidget):
    """One tab's tiles as thumbnails; dragging one carries its tile id."""

    range_dropped = Signal(object)

    def __init__(self) -> None:
        super().__init__()
        self.setViewMode(QListView.ViewMode.IconMode)
        self.setIconSize(QSize(*SIZE))
        self.setGridSize(QSize(SIZE[0] + 14, SIZE[1] + 30))
        self.setResizeMode(QListView.ResizeMode.Adjust)
        self.setMovement(QListView.Movement.Static)
        self.setWordWrap(True)
        self.setDragEnabled(True)
        self.setAcceptDrops(True)
        self.setDragDropMode(QAbstractItemView.DragDropMode.DragDrop)
        self.setSelectionMode(QAbstractItemView.SelectionMode.SingleSelection)

    def mimeData(self, items):  # noqa: N802 - Qt override
        return tile_mime(items[0].data(Qt.ItemDataRole.UserRole)) if items else None

    def dragEnterEvent(self, event) -> None:
        if event.mimeData().hasFormat(RANGE_MIME):
            event.acceptProposedAction()
        else:
            event.ignore()

    def dragMoveEvent(self, event) -> None:
        if event.mimeData().hasFormat(RANGE_MIME):
            event.acceptProposedAction()
        else:
            event.ignore()

    def dropEvent(self, event) -> None:
        if event.mimeData().hasFormat(RANGE_MIME):
            self.range_dropped.emit(event.mimeData())
            event.acceptProposedAction()


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
        bar = QHBoxLayout()
        bar.setContentsMargins(0, 0, 0, 0)
        bar.addWidget(self.name, 1)
        for widget in (self.add_button, self.rename_button, self.remove_button):
            bar.addWidget(widget)
        layout = QVBoxLayout(self)
        layout.setContentsMargins(2, 2, 2, 2)
        layout.addWidget(self.tabs, 1)
        layout.addLayout(bar)
        self._shown: tuple = ()
        self._icons: dict[tuple[str, int], QIcon] = {}
        doc.changed.connect(self.refresh)
        self.refresh()

    def current_tab(self) -> str:
        return self.tabs.tabText(self.tabs.currentIndex())

    def tile_list(self, tab: str) -> TileList:
        for i in range(self.tabs.count()):
            if self.tabs.tabText(i) == tab:
                return self.tabs.widget(i)
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
            widget.deleteLater()
        for tab in project.palette:
            tiles = TileList()
            tiles.range_dropped.connect(
                lambda mime, name=tab.name: self.range_dropped.emit(name, mime)
            )
            tiles.itemClicked.connect(
                lambda item: self.doc.select_tile(item.data(Qt.ItemDataRole.UserRole))
            )
            for tile_id in tab.tile_ids:
                tile = project.tiles[tile_id]
                item = QListWidgetItem(self._icon(tile), tile.name)
                item.setData(Qt.ItemDataRole.UserRole, tile_id)
                item.setToolTip(f"{tile.name}: {tile.duration:.3g} {project.unit}")
                tiles.addItem(item)
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

    def remove_tab(self) -> None:
        """Remove the current user tab (its tiles stay in the library)."""
        self.doc.apply("remove palette tab", edits.remove_tab, self.current_tab())
