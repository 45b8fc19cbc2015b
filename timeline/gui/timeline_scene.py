"""The timeline scene: lane backgrounds, grid, clip items kept in step with the project."""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass

import numpy as np
from PySide6.QtCore import QLineF, QPointF, QRect, QRectF
from PySide6.QtGui import QColor, QPainter, QPen
from PySide6.QtWidgets import (
    QGraphicsLineItem,
    QGraphicsScene,
    QGraphicsSceneHelpEvent,
    QToolTip,
)

from timeline.edits.placement import EPS, covered_spans, overlaps
from timeline.model import Clip, Project, Track
from timeline.plugins.track_kinds import track_kind
from timeline.tiles import Tile

from .clip_item import ClipItem
from .clip_layer import ClipLayer, LaneClips, fill_runs
from .geometry import Geometry, display_factor, nice_step
from .lane_scale import visible_lanes

LANE_COLOURS = (QColor("#f4f4f2"), QColor("#ebebe8"))
LANE_EDGE = QColor("#c8c8c4")
GRID_COLOUR = QColor(0, 0, 0, 25)
EXTRA_LANE_ROOM = 40

# lane height, project rate and whether the track is muted (the zoom changes no clip)
TrackView = tuple[float, float, bool]


@dataclass(frozen=True)
class _TrackShown:
    """The track state a lane's clip items were last updated from."""

    track: Track
    lane: int
    selected: frozenset[str]
    view: TrackView
    tiles: dict[str, Tile]  # tile id -> the tile object its clips were drawn from
    clips: LaneClips  # its clips in start order, for the clip layer

    @property
    def clip_ids(self) -> set[str]:
        return set(self.track.clips_by_id)

    def hatched(self) -> list[ClipItem]:
        """The items of its clips that show a covered span."""
        return [i for i in self.clips.items if i.covered]

    def same(
        self,
        track: Track,
        lane: int,
        selected: frozenset[str],
        view: TrackView,
        tiles: Mapping[str, Tile] | None,
    ) -> bool:
        """True when nothing the items show changed (tiles None: the library is unchanged)."""
        return (
            track is self.track
            and lane == self.lane
            and selected == self.selected
            and view == self.view
            and (tiles is None or all(tiles.get(i) is tile for i, tile in self.tiles.items()))
        )


class TimelineScene(QGraphicsScene):
    """Lanes and clips; `sync` updates only what changed, so a drag never rebuilds the scene.

    The clips are painted by one item (clip_layer.ClipLayer); `items_by_clip` holds what each
    clip shows. Tooltips come from `tip_sources` (the findings' shading) before the items and
    the clips under the mouse.
    """

    def __init__(self, geometry: Geometry) -> None:
        super().__init__()
        self.setItemIndexMethod(QGraphicsScene.ItemIndexMethod.NoIndex)  # a few items, moving
        self.lane_geometry = geometry
        self.layer = ClipLayer(geometry)
        self.addItem(self.layer)
        self.tip_sources: list[Callable[[QPointF], str]] = []
        self._backdrop: object = None  # what the lanes' background was last drawn from
        self.items_by_clip: dict[str, ClipItem] = {}
        self._shown: dict[str, _TrackShown] = {}  # track id -> what its items show
        self._tiles: object = None  # the tile library the items were last updated from
        self.project: Project | None = None
        self.selection: set[str] = set()
        self.min_width = 800.0
        self.playhead = QGraphicsLineItem()
        self.playhead.setPen(QPen(QColor("#d00000"), 1.5))
        self.playhead.setZValue(20)
        self.cursor = QGraphicsLineItem()
        self.cursor.setPen(QPen(QColor("#2050c0"), 1))
        self.cursor.setZValue(19)
        self.addItem(self.playhead)
        self.addItem(self.cursor)
        self.playhead_u = 0.0
        self.cursor_u = 0.0

    def sync(self, project: Project, selection: list[str]) -> None:
        """Show a project state, touching only the clip items of tracks that changed.

        A track is unchanged when it is the same object (edits share untouched tracks) at the
        same lane, its tiles are the same objects, and its selected clips and the zoom are the
        same; its items are then left alone, so a drag on 20,000 clips updates a few items.
        """
        self.project, self.selection = project, set(selection)
        view = (self.lane_geometry.lane_height, project.rate)
        # edits that leave the tile library alone share its map, so its tiles need no check
        tiles = None if project.tiles is self._tiles else project.tiles
        self._tiles = project.tiles
        selected_by_track: dict[str, set[str]] = {}
        for clip_id in self.selection:
            item = self.items_by_clip.get(clip_id)
            if item is not None:
                selected_by_track.setdefault(item.track_id, set()).add(clip_id)
        shown: dict[str, _TrackShown] = {}
        soloing = any(t.solo for t in project.tracks)
        for lane, track in enumerate(project.tracks):
            selected = frozenset(selected_by_track.get(track.id, ()))
            before = self._shown.get(track.id)
            muted = (not track.solo) if soloing else track.mute
            track_view = (*view, muted)  # a mute or solo elsewhere dims or lights this lane
            if before is not None and before.same(track, lane, selected, track_view, tiles):
                shown[track.id] = before
                continue
            shown[track.id] = self._show_track(
                project, track, lane, track_view, before, tiles is None
            )
            if before is not None:
                self._drop_items(before.clip_ids - shown[track.id].clip_ids, track.id)
        for track_id in self._shown.keys() - shown.keys():
            self._drop_items(self._shown[track_id].clip_ids, track_id)
        self._shown = shown
        self.layer.lanes = {lane: shown[t.id].clips for lane, t in enumerate(project.tracks)}
        self.refit()

    def _show_track(
        self,
        project: Project,
        track: Track,
        lane: int,
        view: TrackView,
        before: _TrackShown | None,
        same_tiles: bool,
    ) -> _TrackShown:
        """Update the items of a changed track; clips the edit did not touch are skipped."""
        colour = track_kind(track.kind).colour
        tiles: dict[str, Tile] = {}
        unchanged: dict[str, Clip] = {}
        if before is not None and same_tiles and before.lane == lane and before.view == view:
            unchanged = before.track.clips_by_id
            tiles = dict(before.tiles)
        if unchanged and before is not None:
            shown = self._move_items(project, track, before, tiles, colour)
            if shown is not None:
                return shown
        covered = overlaps(project, track.id)
        muted = view[-1]
        for clip in track.clips:
            if (
                before is not None
                and unchanged.get(clip.id) is clip
                and (clip.id in self.selection) == (clip.id in before.selected)
                and self.items_by_clip[clip.id].covered == covered.get(clip.id, ())
            ):
                continue
            tile = tiles.get(clip.tile_id)
            if tile is None:
                tile = tiles[clip.tile_id] = project.tile(clip.tile_id)
            item = self.items_by_clip.get(clip.id)
            before_rect = None if item is None or before is None else item.sceneBoundingRect()
            if item is None:
                item = self.items_by_clip[clip.id] = ClipItem(self.lane_geometry, clip, tile)
            changed = item.update_from(
                clip,
                tile,
                track.id,
                lane,
                colour,
                project.rate,
                clip.id in self.selection,
                muted,
                covered.get(clip.id, ()),
                project.axis,
            )
            if changed and before is not None:
                self.update(item.sceneBoundingRect())
                if before_rect is not None:
                    self.update(before_rect)
        if before is None:  # a track shown anew (all of them on opening): one repaint of the
            self.update()  # whole scene rather than one per clip (20,000 on a large project)
        selected = frozenset(c.id for c in track.clips if c.id in self.selection)
        clips = LaneClips([self.items_by_clip[c.id] for c in track.clips])
        return _TrackShown(track, lane, selected, view, tiles, clips)

    def _move_items(
        self,
        project: Project,
        track: Track,
        before: _TrackShown,
        tiles: dict[str, Tile],
        colour: str,
    ) -> _TrackShown | None:
        """A track whose clips changed but none came or went (a drag along it): update the
        changed clips' items and those whose covered span changed, and put the changed ones
        where they now start, without a walk over the lane's items. None: do it all again."""
        old = before.track.clips_by_id
        if len(old) != len(track.clips) or track.clips_by_id.keys() != old.keys():
            return None
        selected = frozenset(i for i in self.selection if i in track.clips_by_id)
        changed = [c for c in track.clips if old[c.id] is not c]
        if not changed or selected != before.selected:
            return None  # nothing moved, or the selection did: the full update decides
        items = [self.items_by_clip[c.id] for c in changed]
        starts = [old[c.id].start for c in changed]
        for clip, item in zip(changed, items, strict=True):
            self._show_clip(project, track, clip, item, tiles, colour, before.view, item.covered)
        clips = before.clips.moved(starts, items)
        if clips is None:
            return None
        lo, hi = covered_spans(clips.starts, clips.ends)
        now = {clips.items[i].clip.id: i for i in np.flatnonzero(hi - lo > EPS).tolist()}
        for item in {*items, *(clips.items[i] for i in now.values()), *before.hatched()}:
            i = now.get(item.clip.id)
            covered = () if i is None else ((float(lo[i]), float(hi[i])),)
            if covered != item.covered:
                self._show_clip(
                    project, track, item.clip, item, tiles, colour, before.view, covered
                )
        return _TrackShown(track, before.lane, before.selected, before.view, tiles, clips)

    def _show_clip(
        self,
        project: Project,
        track: Track,
        clip: Clip,
        item: ClipItem,
        tiles: dict[str, Tile],
        colour: str,
        view: TrackView,
        covered: tuple[tuple[float, float], ...],
    ) -> None:
        """Update one clip's item and repaint where it was and is."""
        tile = tiles.get(clip.tile_id)
        if tile is None:
            tile = tiles[clip.tile_id] = project.tile(clip.tile_id)
        before_rect = item.sceneBoundingRect()
        changed = item.update_from(
            clip,
            tile,
            track.id,
            item.lane,
            colour,
            project.rate,
            clip.id in self.selection,
            view[-1],
            covered,
            project.axis,
        )
        if changed:
            self.update(item.sceneBoundingRect())
            self.update(before_rect)

    def _drop_items(self, clip_ids: Iterable[str], track_id: str) -> None:
        """Remove the items of clips that left a track (unless another track now shows them)."""
        for clip_id in clip_ids:
            item = self.items_by_clip.get(clip_id)
            if item is not None and item.track_id == track_id:
                self.update(self.items_by_clip.pop(clip_id).sceneBoundingRect())

    def refit(self) -> None:
        """Size the scene to the lanes and the project (plus room to drag past the end)."""
        g = self.lane_geometry
        lanes = len(self.project.tracks) if self.project else 0
        width = max(
            self.min_width, g.x((self.project.duration if self.project else 0) * 1.25) + 200
        )
        height = g.lane_top(lanes) + EXTRA_LANE_ROOM
        self.setSceneRect(QRectF(0, 0, width, height))
        self.layer.resize(self.sceneRect())
        self.set_playhead(self.playhead_u)
        self.set_cursor(self.cursor_u)
        backdrop = self._backdrop_key()
        if backdrop != self._backdrop:  # the lanes, grid, loop or scales changed: all of it
            self._backdrop = backdrop
            self.update()

    def _backdrop_key(self) -> tuple[object, ...]:
        """What the background, the lanes' scales and the clip layer's zoom depend on."""
        g, project = self.lane_geometry, self.project
        if project is None:
            return (g.px_per_unit, g.lane_height)
        tracks = tuple((t.kind, t.full_scale, t.name) for t in project.tracks)
        return (g.px_per_unit, g.lane_height, tracks, project.loop, project.axis)

    def clip_at(self, pos: QPointF) -> ClipItem | None:
        """The clip under a scene position (the one drawn on top)."""
        return self.layer.clip_at(pos)

    def helpEvent(self, event: QGraphicsSceneHelpEvent) -> None:  # noqa: N802 - Qt's name
        """The tooltip under the mouse: a finding's, an item's, else the clip's."""
        pos = event.scenePos()
        text = next((t for source in self.tip_sources if (t := source(pos))), "")
        if not text:
            text = next((i.toolTip() for i in self.items(pos) if i.toolTip()), "")
        if not text:
            clip = self.clip_at(pos)
            text = clip.toolTip() if clip is not None else ""
        if text:
            QToolTip.showText(event.screenPos(), text, event.widget())
        else:
            QToolTip.hideText()
        event.setAccepted(bool(text))

    def set_playhead(self, u: float) -> None:
        """Move the playhead line."""
        self.playhead_u = u
        x = self.lane_geometry.x(u)
        self.playhead.setLine(QLineF(x, 0, x, self.sceneRect().height()))

    def set_cursor(self, u: float) -> None:
        """Move the edit cursor (where split cuts)."""
        self.cursor_u = u
        x = self.lane_geometry.x(u)
        self.cursor.setLine(QLineF(x, 0, x, self.sceneRect().height()))

    def drawBackground(self, painter: QPainter, exposed: QRectF | QRect) -> None:
        rect = QRectF(exposed)
        g = self.lane_geometry
        lanes = len(self.project.tracks) if self.project else 0
        painter.setRenderHint(QPainter.RenderHint.Antialiasing, False)  # lines on pixels
        painter.fillRect(rect, QColor("#d9d9d6"))
        for lane in visible_lanes(g, lanes, rect):
            band = QRectF(rect.left(), g.lane_top(lane), rect.width(), g.lane_height)
            painter.fillRect(band, LANE_COLOURS[lane % 2])
            # pixel-wide fills, not blended lines: they cost a twentieth
            painter.fillRect(QRectF(rect.left(), band.bottom(), rect.width(), 1), LANE_EDGE)
        if self.project is None or lanes == 0:
            return
        factor = display_factor(self.project.axis)
        step = nice_step(g.px_per_unit / factor) / factor
        first = math.floor(g.u(rect.left()) / step)
        last = math.ceil(g.u(rect.right()) / step)
        bottom = g.lane_top(lanes)
        loop = self.project.loop
        if loop is not None:
            band = QRectF(g.x(loop.start), 0, g.x(loop.stop) - g.x(loop.start), bottom)
            painter.fillRect(band.intersected(rect), QColor(56, 160, 90, 30))
        top, height = max(0.0, rect.top()), min(bottom, rect.bottom()) - max(0.0, rect.top())
        # one picture for all the grid lines: a blended pixel-wide column cost 0.12-0.16 ms each
        columns = sorted({round(g.x(i * step)) for i in range(first, last + 1)})
        fill_runs(painter, [(float(x), x + 1.0) for x in columns], top, height, GRID_COLOUR)

    def grid_step(self) -> float:
        """The grid spacing in axis units at the current zoom (what snapping lands on)."""
        factor = display_factor(self.project.axis if self.project else "time")
        return nice_step(self.lane_geometry.px_per_unit / factor) / factor / 4
