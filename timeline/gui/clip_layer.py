"""The clips of every lane, painted by one scene item that draws only what is exposed.

Zooming a 20,000-clip project used to update every clip's QGraphicsItem (0.9-1.4 s a step) and
a repaint walked them all; here a zoom changes no clip and a paint finds the visible clips of each
visible lane by bisection. A lane showing BATCH_FROM clips or more draws them as boxes in a few
calls (narrow ones and their grab flags merged into runs of pixels), so a whole project at fit
costs the same as a few clips; a lane showing fewer draws each clip's waveform, fades and label
(level of detail: zoom in on a crowded lane to see its waves).
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from functools import cache, cached_property
from typing import cast

import numpy as np
from PySide6.QtCore import QPointF, QRect, QRectF, Qt
from PySide6.QtGui import QBrush, QColor, QImage, QPainter, QPen, QPolygonF
from PySide6.QtWidgets import QGraphicsItem

from .clip_item import GRAB_PX, ClipItem
from .geometry import CLIP_MARGIN, Geometry

BATCH_FROM = 8  # clips visible on a lane from which they are drawn as boxes


class LaneClips:
    """One lane's clips in start order, with their starts and ends as arrays for bisection."""

    def __init__(self, items: Sequence[ClipItem], arrays: tuple[np.ndarray, ...] = ()) -> None:
        ordered = sorted(items, key=lambda item: item.clip.start) if not arrays else list(items)
        self.items = ordered
        if arrays:  # already in order, with their starts and ends (moved)
            self.starts, self.ends = arrays
        else:
            self.starts = np.array([i.clip.start for i in ordered], dtype=np.float64)
            self.ends = np.array([i.clip.end for i in ordered], dtype=np.float64)
        self.longest = float((self.ends - self.starts).max()) if ordered else 0.0
        self.muted = bool(ordered) and ordered[0].muted
        self.colour = ordered[0].colour if ordered else QColor("#888888")

    @cached_property
    def selected(self) -> np.ndarray:
        """Which clips are selected (a lane whose selection changes gets new LaneClips)."""
        return np.array([item.selected for item in self.items], dtype=bool)

    def moved(self, starts: Sequence[float], items: Sequence[ClipItem]) -> LaneClips | None:
        """These clips' items (updated in place; `starts`: where they started) put where they
        now start, without sorting the lane again; None when two clips would start together
        (their order is then the track's, which a full sort keeps)."""
        at = [int(np.searchsorted(self.starts, start)) for start in starts]
        if any(
            i >= len(self.items) or self.items[i] is not item
            for i, item in zip(at, items, strict=True)
        ):
            return None
        kept = np.ones(len(self.items), dtype=bool)
        kept[at] = False
        rest = [item for item, keep in zip(self.items, kept.tolist(), strict=True) if keep]
        starts_left, ends_left = self.starts[kept], self.ends[kept]
        new_starts = np.array([i.clip.start for i in items], dtype=np.float64)
        new_ends = np.array([i.clip.end for i in items], dtype=np.float64)
        order = np.argsort(new_starts, kind="stable")
        where = np.searchsorted(starts_left, new_starts[order])
        ordered = np.insert(starts_left, where, new_starts[order])
        if ordered.size > 1 and not (np.diff(ordered) > 0).all():
            return None
        for offset, (i, j) in enumerate(zip(where.tolist(), order.tolist(), strict=True)):
            rest.insert(i + offset, items[j])
        ends = np.insert(ends_left, where, new_ends[order])
        return LaneClips(rest, (ordered, ends))

    def between(self, u0: float, u1: float) -> np.ndarray:
        """Indices of the clips that reach into [u0, u1] (axis units)."""
        first = int(np.searchsorted(self.starts, u0 - self.longest, side="left"))
        last = int(np.searchsorted(self.starts, u1, side="right"))
        found = np.arange(first, last)
        return found[self.ends[first:last] >= u0]


def runs(left: np.ndarray, right: np.ndarray) -> list[tuple[float, float]]:
    """The union of the spans [left, right) as sorted, disjoint (start, stop) runs."""
    if left.size == 0:
        return []
    order = np.argsort(left, kind="stable")
    a, b = left[order], np.maximum.accumulate(right[order])
    breaks = np.flatnonzero(a[1:] > b[:-1]) + 1
    starts = np.concatenate(([0], breaks))  # not np.r_: 10x the cost at this size
    stops = np.concatenate((breaks - 1, [a.size - 1]))
    return list(zip(a[starts].tolist(), b[stops].tolist(), strict=True))


class ClipLayer(QGraphicsItem):
    """Paints the clips of the lanes the scene holds (`lanes`: lane index -> LaneClips)."""

    def __init__(self, geometry: Geometry) -> None:
        super().__init__()
        self.lane_geometry = geometry
        self.lanes: dict[int, LaneClips] = {}
        self._rect = QRectF()
        self.setZValue(1)
        self.setAcceptedMouseButtons(Qt.MouseButton.NoButton)
        self.setFlag(QGraphicsItem.GraphicsItemFlag.ItemUsesExtendedStyleOption)

    def resize(self, rect: QRectF) -> None:
        """Cover the scene rectangle."""
        if rect != self._rect:
            self.prepareGeometryChange()
            self._rect = QRectF(rect)

    def boundingRect(self) -> QRectF:  # noqa: N802 - Qt's name
        return self._rect

    def visible(self, exposed: QRectF) -> list[tuple[int, LaneClips, np.ndarray]]:
        """(lane, its clips, indices of those in `exposed`) for the lanes `exposed` crosses."""
        g = self.lane_geometry
        pad = GRAB_PX
        u0, u1 = g.u(exposed.left() - pad), g.u(exposed.right() + pad)
        first, last = g.lane_at(exposed.top()), g.lane_at(exposed.bottom())
        return [
            (lane, clips, clips.between(u0, u1))
            for lane, clips in self.lanes.items()
            if first <= lane <= last
        ]

    def paint(self, painter: QPainter, option, widget=None) -> None:  # noqa: ANN001
        exposed = option.exposedRect
        parts = _painted_parts(painter, exposed)
        inside: dict[int, list[np.ndarray]] = {}  # lane -> clips in the parts Qt really paints
        for part in parts if len(parts) > 1 else ():
            for lane, _, found in self.visible(part):
                inside.setdefault(lane, []).append(found)
        shown = self._shown_range(painter, widget, exposed)
        for lane, clips, found in self.visible(exposed):
            if found.size == 0:
                continue
            painter.setOpacity(0.35 if clips.muted else 1.0)
            # the level of detail of what the view shows of the lane, not of the part repainted:
            # a dragged clip repainted alone is drawn as the rest of its crowded lane is
            batch = clips.between(*shown).size >= BATCH_FROM
            if len(parts) > 1:  # the rest would be drawn only to be clipped away
                found = np.intersect1d(found, np.concatenate([*inside.get(lane, []), found[:0]]))
                if found.size == 0:
                    continue
            if batch:
                self._paint_boxes(painter, lane, clips, found)
                continue
            items = [clips.items[i] for i in found.tolist()]
            # selected clips on top, as their items were
            for item in sorted(items, key=lambda item: item.selected):
                pos = item.pos()
                painter.save()
                painter.translate(pos)
                item.paint(painter, exposed.translated(-pos))
                painter.restore()
        painter.setOpacity(1.0)

    def _shown_range(self, painter: QPainter, widget, exposed: QRectF) -> tuple[float, float]:  # noqa: ANN001
        """The axis range the view shows (the painted widget's rectangle in scene units, a
        narrow clip's grab area beyond each side); `exposed` when painted into no widget."""
        shown = exposed
        if widget is not None:
            inverse, invertible = painter.worldTransform().inverted()
            if invertible:
                shown = inverse.mapRect(QRectF(widget.rect()))
        g = self.lane_geometry
        return g.u(shown.left() - GRAB_PX), g.u(shown.right() + GRAB_PX)

    def _paint_boxes(
        self, painter: QPainter, lane: int, clips: LaneClips, found: np.ndarray
    ) -> None:
        """Many clips on a lane: boxes (narrow ones and their grab flags merged into runs of
        pixels), no waveform or label, a few drawing calls whatever the count."""
        g = self.lane_geometry
        top = g.lane_top(lane) + CLIP_MARGIN
        h = g.lane_height - 2 * CLIP_MARGIN
        x0 = clips.starts[found] * g.px_per_unit
        x1 = np.maximum(clips.ends[found] * g.px_per_unit, x0 + 2.0)
        narrow = (x1 - x0) < GRAB_PX
        colour = clips.colour
        painter.save()
        painter.setRenderHint(QPainter.RenderHint.Antialiasing, False)  # whole pixels
        fill = QColor(colour)
        fill.setAlpha(90)
        painter.setBrush(QBrush(fill))
        painter.setPen(QPen(colour.darker(130), 1))
        wide = zip(x0[~narrow].tolist(), x1[~narrow].tolist(), strict=True)
        painter.drawRects([QRectF(a, top, b - a, h) for a, b in wide])
        fill.setAlpha(130)  # runs of narrow clips: filled, not outlined (the outlines of
        # hundreds of runs cost more than their fill), as one picture (one rectangle each cost
        # 6 us, 5.6 ms of a repaint at fit on 20,000 clips)
        fill_runs(painter, runs(x0[narrow], x1[narrow]), top, h, fill)
        painter.setPen(QPen(colour.darker(130), 1))
        painter.setBrush(QBrush(colour))
        middle = (x0[narrow] + x1[narrow]) / 2
        half = GRAB_PX / 2
        flag = _flag(GRAB_PX, half)  # a lone narrow clip's, moved to each (no new points)
        for a, b in runs(middle - half, middle + half):
            lone = abs(b - a - GRAB_PX) < 1e-9  # (m + 5) - (m - 5) is 10 give or take 1e-15
            polygon = flag if lone else _flag(b - a, min(half, (b - a) / 2))
            painter.drawPolygon(polygon.translated(a, top))
        selected = [clips.items[i] for i in found[clips.selected[found]].tolist()]
        if selected:
            painter.setBrush(Qt.BrushStyle.NoBrush)
            painter.setPen(QPen(QColor("#1a1a1a"), 2))
            painter.drawRects([i.sceneBoundingRect() for i in selected])
        painter.restore()

    def clip_at(self, pos: QPointF) -> ClipItem | None:
        """The clip drawn on top at a scene position (within a narrow clip's grab area)."""
        g = self.lane_geometry
        clips = self.lanes.get(g.lane_at(pos.y()))
        if clips is None:
            return None
        found = clips.between(g.u(pos.x() - GRAB_PX), g.u(pos.x() + GRAB_PX))
        hits = [
            clips.items[i]
            for i in found.tolist()
            if clips.items[i].sceneBoundingRect().contains(pos)
        ]
        # the one the pointer is over (a grab area reaches beyond a clip's ends), then the topmost:
        # selected first, then the one drawn last
        return (
            max(enumerate(hits), key=lambda h: (_over(h[1], pos), h[1].selected, h[0]))[1]
            if hits
            else None
        )


def _flag(width: float, inset: float) -> QPolygonF:
    """The grab flag over narrow clips, `width` wide at the top, at the origin."""
    return QPolygonF(
        [QPointF(0, 0), QPointF(width, 0), QPointF(width - inset, GRAB_PX), QPointF(inset, GRAB_PX)]
    )


def fill_runs(
    painter: QPainter, spans: list[tuple[float, float]], top: float, height: float, colour: QColor
) -> None:
    """Fill disjoint spans [a, b), each a pixel wide or more, of one row of the scene (from `top`,
    `height` high) with a colour as one image, with the pixels QPainter fills for an unclipped
    rectangle without antialiasing under a translation: the columns from round(a) up to round(b)
    (halves rounded up; Qt's rasterizer, which it uses for clipped rectangles, rounds them down)."""
    if not spans:
        return
    edges = np.floor(np.array(spans, dtype=np.float64) + 0.5).astype(np.int64)
    first, last = int(edges[0, 0]), int(edges[-1, 1])
    if last <= first:
        return
    step = np.zeros(last - first + 1, dtype=np.int64)
    step[edges[:, 0] - first] += 1  # disjoint spans: no two start (or end) on one column
    step[edges[:, 1] - first] -= 1
    row = np.where(np.cumsum(step)[:-1] > 0, _premultiplied(colour.rgba(), painter.opacity()), 0)
    row0 = np.floor(top + 0.5)
    rows = np.floor(top + height + 0.5) - row0
    if rows <= 0:
        return
    pixels = np.ascontiguousarray(row, dtype=np.uint32)
    image = QImage(
        pixels.data, pixels.size, 1, 4 * pixels.size, QImage.Format.Format_ARGB32_Premultiplied
    )
    opacity = painter.opacity()
    painter.setOpacity(1.0)  # already in the pixels, as a fill with this opacity blends them
    # the row stretched down (each pixel repeated, not interpolated)
    target = QRectF(first, float(row0), float(pixels.size), float(rows))
    painter.drawImage(target, image, QRectF(0, 0, pixels.size, 1))
    painter.setOpacity(opacity)


@cache
def _premultiplied(rgba: int, opacity: float) -> int:
    """The premultiplied pixel Qt blends for a fill of this colour (QColor.rgba) at this
    opacity."""
    pixel = QImage(1, 1, QImage.Format.Format_ARGB32_Premultiplied)
    pixel.fill(0)
    painter = QPainter(pixel)
    painter.setOpacity(opacity)
    painter.fillRect(QRectF(0, 0, 1, 1), QColor.fromRgba(rgba))
    painter.end()
    return int(np.frombuffer(pixel.constBits(), dtype=np.uint32, count=1)[0])


def _painted_parts(painter: QPainter, exposed: QRectF) -> list[QRectF]:
    """The rectangles of `exposed` that this paint really covers, in the painter's coordinates.

    Qt hands an item the bounding rectangle of what is repainted: a dragged clip's rectangles
    and the full-height snap line make it the height of the lanes, and every clip in it would be
    drawn only to be clipped away. The paint's region (the engine's system clip) says which
    parts count; one part, or none known, is `exposed` itself.
    """
    engine = painter.paintEngine()
    region = engine.systemClip() if engine is not None else None
    if region is None or region.rectCount() < 2:
        return [exposed]
    inverse, invertible = painter.deviceTransform().inverted()
    if not invertible:
        return [exposed]
    rects = cast("Iterable[QRect]", region)  # QRegion iterates its rectangles; its stubs omit it
    parts = [inverse.mapRect(QRectF(rect)).intersected(exposed) for rect in rects]
    return [part for part in parts if not part.isEmpty()] or [exposed]


def _over(item: ClipItem, pos: QPointF) -> bool:
    """Whether a scene position lies within the clip itself, not only its grab area."""
    return 0.0 <= item.mapFromScene(pos).x() < item.width()
