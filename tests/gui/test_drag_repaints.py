"""A clip drag repaints only what shows the clip: the lanes and the inspector's clip fields, not
the ruler, the palette, the track headers, the waveform editor, the transport or the tile's
fields (paint events counted; the time a drag takes is measured by `haptic-timeline bench
editor`), and what it repaints looks as a fresh paint of the whole window would."""

from __future__ import annotations

from collections import Counter

import pytest
from PySide6.QtCore import QEvent, QObject, QPoint, Qt
from PySide6.QtGui import QImage
from PySide6.QtTest import QTest
from PySide6.QtWidgets import QApplication, QWidget

from timeline import edits

from .helpers import clip_point, painted_and_fresh, pixel_array

LEFT, NO = Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier


class PaintCounter(QObject):
    """Counts paint events by which of `areas` (name -> widget) the painted widget is in."""

    def __init__(self, areas: dict[str, QWidget]) -> None:
        super().__init__()
        self.areas = areas
        self.counts: Counter[str] = Counter()

    def eventFilter(self, watched: QObject, event: QEvent) -> bool:  # noqa: N802 - Qt's name
        if event.type() == QEvent.Type.Paint and isinstance(watched, QWidget):
            for name, area in self.areas.items():
                if watched is area or area.isAncestorOf(watched):
                    self.counts[name] += 1
        return False


@pytest.fixture
def areas(window) -> dict[str, QWidget]:
    win = window
    inspector = win.inspector
    return {
        "palette": win.tile_palette,
        "track headers": win.headers,
        "waveform editor": win.editor,
        "transport": win.transport,
        "tile fields": inspector.title,
        **{f"tile {name}": box for name, box in inspector.boxes.items()},
        "ruler": win.ruler,
        "clip fields": inspector.pages["clip"],
        "lanes": win.view.viewport(),
    }


def test_a_clip_drag_repaints_only_the_lanes_and_the_clip_fields(window, areas):
    win = window
    clip_id = win.ids["c1"]
    at = clip_point(win, clip_id)
    viewport = win.view.viewport()
    QTest.mousePress(viewport, LEFT, NO, at)
    QApplication.processEvents()  # the press selects the clip: its tile and fields show
    assert win.doc.selected_clips == [clip_id] and win.inspector.boxes
    start = win.doc.project.find_clip(clip_id)[1].start
    counter = PaintCounter(areas)
    app = QApplication.instance()
    app.installEventFilter(counter)
    try:
        for step in range(1, 9):
            QTest.mouseMove(viewport, at + QPoint(5 * step, 0))
            QApplication.processEvents()
    finally:
        app.removeEventFilter(counter)
        QTest.mouseRelease(viewport, LEFT, NO, at + QPoint(40, 0))
    moved = win.doc.project.find_clip(clip_id)[1].start - start
    assert moved == pytest.approx(40 / win.view.lane_geometry.px_per_unit)
    counts = counter.counts
    assert counts["lanes"] >= 8 and counts["clip fields"] >= 8  # the clip moved, its start shown
    quiet = {name: counts[name] for name in areas if name not in ("lanes", "clip fields")}
    assert quiet == dict.fromkeys(quiet, 0)


def _pixels(image: QImage) -> bytes:
    return image.convertToFormat(QImage.Format.Format_RGB32).constBits().tobytes()


def test_a_clip_dragged_on_a_crowded_lane_is_drawn_as_a_fresh_paint_draws_it(window):
    """On a lane showing many clips they are boxes; the repaint of a dragged clip alone drew it
    (and the clips under the snap line) with its wave, fades and label, until a full paint."""
    win = window
    t1, sine = win.ids["t1"], win.ids["sine"]
    items = [(t1, sine, 1.6 + 0.25 * i, {"source_out": 0.2}) for i in range(12)]
    project, added = edits.add_clips(win.doc.project, items)
    win.doc.replace("add clips", project)
    win.view.snapping = True  # the snap line's strip across the lanes is repainted too
    QApplication.processEvents()
    viewport = win.view.viewport()
    at = clip_point(win, added[5])
    QTest.mousePress(viewport, LEFT, NO, at)
    for step in range(1, 6):
        QTest.mouseMove(viewport, at + QPoint(4 * step, 0))
        QApplication.processEvents()
    assert win.doc.project.find_clip(added[5])[1].start != 1.6 + 0.25 * 5
    painted, fresh = painted_and_fresh(win)
    QTest.mouseRelease(viewport, LEFT, NO, at + QPoint(20, 0))
    assert painted.size() == fresh.size()
    assert _pixels(painted) == _pixels(fresh)


def test_a_selected_clip_dragged_on_a_sparse_lane_leaves_no_trail(window):
    """A lane of one clip draws it whole, its fade handles too: handles centred on the clip's
    ends reached 4 px beyond its rectangle (all a moved clip repaints) and were left behind at
    each move of a drag. Outside the clip (and its outline's pixel, which a clip at 64.99999 px
    rounds either side) what the window holds is what a fresh paint draws."""
    win = window
    viewport = win.view.viewport()
    at = clip_point(win, win.ids["c1"])
    QTest.mousePress(viewport, LEFT, NO, at)
    for step in range(1, 6):
        QTest.mouseMove(viewport, at + QPoint(-7 * step, 0))
        QApplication.processEvents()
    painted, fresh = painted_and_fresh(win)
    rect = win.view.mapFromScene(win.view.clip_scene_rect(win.ids["c1"])).boundingRect()
    QTest.mouseRelease(viewport, LEFT, NO, at + QPoint(-35, 0))
    assert win.doc.project.find_clip(win.ids["c1"])[1].start == pytest.approx(0.5 - 35 / 200)
    before, after = (pixel_array(p) for p in (painted, fresh))
    differs = (before != after).any(axis=2)
    differs[rect.top() - 1 : rect.bottom() + 2, rect.left() - 1 : rect.right() + 2] = False
    assert differs.sum() == 0
