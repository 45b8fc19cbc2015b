"""The similarity map in the editor: the project's variants or a palette tab's tiles, by feel.

The same distances and classical MDS map as `haptic-timeline compare` (timeline/similarity/),
drawn with QPainter: a point per icon, red lines between icons closer than one JND, and a table
of the distances. A window beside the editor, not a modal dialog; Refresh measures again.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from PySide6.QtCore import QPointF, QRectF, Qt
from PySide6.QtGui import QColor, QPainter, QPen
from PySide6.QtWidgets import (
    QHBoxLayout,
    QLabel,
    QPushButton,
    QTableWidget,
    QTableWidgetItem,
    QVBoxLayout,
    QWidget,
)

from timeline.errors import HapticTimelineError
from timeline.model import Project
from timeline.similarity.compare import Comparison, compare
from timeline.similarity.distance import ALIKE
from timeline.similarity.labels import label_groups

MARGIN = 40.0
ALIKE_COLOUR = QColor("#c0392b")


class MapCanvas(QWidget):
    """The 2-D map: icons as points, too-alike pairs joined in red, a 1-JND scale bar."""

    def __init__(self) -> None:
        super().__init__()
        self.comparison: Comparison | None = None
        self.setMinimumSize(360, 320)

    def show_comparison(self, comparison: Comparison) -> None:
        self.comparison = comparison
        self.update()

    def points(self) -> dict[str, QPointF]:
        """Widget position of each icon (equal scale on both axes)."""
        c = self.comparison
        if c is None or not c.names:
            return {}
        xy = c.coords
        lo, hi = xy.min(axis=0), xy.max(axis=0)
        span = float(max((hi - lo).max(), ALIKE))
        scale = min(self.width() - 2 * MARGIN, self.height() - 2 * MARGIN) / span
        centre = (lo + hi) / 2.0
        mid = np.array([self.width() / 2.0, self.height() / 2.0])
        return {
            name: QPointF(*(mid + (p - centre) * np.array([scale, -scale])))
            for name, p in zip(c.names, xy, strict=True)
        }

    def jnd_pixels(self) -> float:
        c = self.comparison
        if c is None or not c.names:
            return 0.0
        xy = c.coords
        span = float(max((xy.max(axis=0) - xy.min(axis=0)).max(), ALIKE))
        return min(self.width() - 2 * MARGIN, self.height() - 2 * MARGIN) / span

    def paintEvent(self, event) -> None:  # noqa: ANN001, N802 - Qt's name
        painter = QPainter(self)
        painter.setRenderHint(QPainter.RenderHint.Antialiasing)
        painter.fillRect(self.rect(), QColor("#fbfbfa"))
        if self.comparison is None:
            painter.drawText(self.rect(), Qt.AlignmentFlag.AlignCenter, "Nothing measured yet")
            return
        points = self.points()
        painter.setPen(QPen(ALIKE_COLOUR, 2.0))
        for a, b, d in self.comparison.too_alike():
            painter.drawLine(points[a], points[b])
            painter.drawText((points[a] + points[b]) / 2 + QPointF(-10, 18), f"{d:.2f}")
        painter.setPen(QPen(QColor("#2c3e50"), 1.0))
        painter.setBrush(QColor("#2c3e50"))
        for p in points.values():
            painter.drawEllipse(p, 5.0, 5.0)
        xy = np.array([[p.x(), -p.y()] for p in points.values()])
        for n, (names, (x, y)) in enumerate(label_groups(list(points), xy)):
            painter.drawText(
                QPointF(x, -y) + QPointF(8, -6 if n % 2 == 0 else 14), " / ".join(names)
            )
        bar = self.jnd_pixels()
        y = self.height() - 14.0
        painter.setPen(QPen(QColor("#555555"), 2.0))
        painter.drawLine(QPointF(MARGIN, y), QPointF(MARGIN + bar, y))
        painter.drawText(QRectF(MARGIN + bar + 6, y - 10, 120, 20),
                         Qt.AlignmentFlag.AlignVCenter, "1 JND")  # fmt: skip


class SimilarityMap(QWidget):
    """A window with the map, the distance table and a Refresh button."""

    def __init__(self, title: str, icons: Callable[[], list[tuple[str, Project]]]) -> None:
        super().__init__()
        self.setWindowTitle(title)
        self.icons = icons
        self.canvas = MapCanvas()
        self.table = QTableWidget()
        self.status = QLabel()
        self.status.setWordWrap(True)
        refresh = QPushButton("Refresh")
        refresh.clicked.connect(self.refresh)
        top = QHBoxLayout()
        top.addWidget(self.status, 1)
        top.addWidget(refresh)
        body = QHBoxLayout()
        body.addWidget(self.canvas, 3)
        body.addWidget(self.table, 2)
        layout = QVBoxLayout(self)
        layout.addLayout(top)
        layout.addLayout(body, 1)
        self.resize(900, 480)
        self.refresh()

    def refresh(self) -> None:
        """Measure the icons again and redraw."""
        try:
            comparison = compare(self.icons())
        except HapticTimelineError as exc:
            self.status.setText(f"Cannot compare: {exc}")
            return
        self.canvas.show_comparison(comparison)
        n = len(comparison.names)
        self.table.setRowCount(n)
        self.table.setColumnCount(n)
        self.table.setHorizontalHeaderLabels(comparison.names)
        self.table.setVerticalHeaderLabels(comparison.names)
        for i in range(n):
            for j in range(n):
                item = QTableWidgetItem(f"{comparison.matrix[i, j]:.2f}")
                if i != j and comparison.matrix[i, j] < ALIKE:
                    item.setForeground(ALIKE_COLOUR)
                self.table.setItem(i, j, item)
        alike = comparison.too_alike()
        self.status.setText(
            f"{n} icons, distances in JNDs; the map keeps {100 * comparison.explained:.0f} % of "
            "the variance. "
            + (
                "Too alike: " + ", ".join(f"{a} and {b} ({d:.2f})" for a, b, d in alike)
                if alike
                else "Every pair is at least 1 JND apart."
            )
        )


def similarity_window(window, source: str) -> SimilarityMap:  # noqa: ANN001 - the main window
    """Open (and keep) a map of the document's variants or of the palette's current tab."""
    from timeline.similarity.icons import tab_icons, variant_icons

    doc = window.doc
    if source == "variants":
        title, icons = "Variants by feel", lambda: variant_icons(doc.project)
    else:
        tab = window.tile_palette.current_tab()
        title, icons = f"Palette tab {tab!r} by feel", lambda: tab_icons(doc.project, tab)
    panel = SimilarityMap(title, icons)
    window.similarity_maps = [*getattr(window, "similarity_maps", []), panel]
    panel.show()
    return panel
