"""Arranging commands on the keyboard: nudge by a grid step, duplicate into a free spot,
split at the playhead, markers at the playhead and jumps between them."""

from __future__ import annotations

from collections.abc import Callable

from timeline import edits
from timeline.edits import markers
from timeline.edits.placement import free_start
from timeline.edits.vibration import emphasis_of, with_emphasis
from timeline.model import Project

from .document import Document
from .geometry import axis_text
from .ruler import Ruler
from .timeline_view import TimelineView


class Arrange:
    """Keyboard edits on the selection, the playhead and the markers (each one undo step)."""

    def __init__(
        self, doc: Document, view: TimelineView, ruler: Ruler, playing: Callable[[], bool]
    ) -> None:
        self.doc, self.view, self.ruler, self.playing = doc, view, ruler, playing

    def here(self) -> float:
        """Where keyboard commands act: the playhead while playing, the edit cursor otherwise."""
        scene = self.view.scene()
        return scene.playhead_u if self.playing() else scene.cursor_u

    def nudge(self, steps: int) -> None:
        """Move the selected clips (a design with its emphasis) by whole grid steps
        (Alt+Left/Right)."""
        ids = with_emphasis(self.doc.project, self.doc.selected_clips)
        if not ids:
            self.doc.message.emit("select clips to nudge", "error")
            return
        step = steps * self.view.scene().grid_step()

        def moved(project: Project) -> Project:
            starts = [project.find_clip(i)[1].start for i in ids]
            shift = max(step, -min(starts))  # the earliest clip stops at 0
            return edits.shift_clips(project, ids, shift)

        if self.doc.apply("nudge", moved):
            axis = self.doc.project.axis
            self.doc.message.emit(f"nudged by {axis_text(step, axis)} (Ctrl+Z undoes)", "info")

    def duplicate(self) -> None:
        """Copy each selected clip into the first gap after it that fits it (Ctrl+D); a design's
        emphasis clips are copied with it, as far along as it."""
        ids = list(self.doc.selected_clips)
        if not ids:
            self.doc.message.emit("select a clip first", "error")
            return
        copies: list[str] = []

        def duplicated(project: Project) -> Project:
            carried = {clip_id: emphasis_of(project, clip_id) for clip_id in ids}
            along = {c for group in carried.values() for c in group}
            for clip_id in (c for c in ids if c not in along):
                track, clip = project.find_clip(clip_id)
                at = free_start(project, track.id, clip.duration, clip.end)
                project, new_id = edits.duplicate_clip(project, clip_id, at)
                copies.append(new_id)
                for accent in carried[clip_id]:
                    shifted = project.find_clip(accent)[1].start + at - clip.start
                    project, new_id = edits.duplicate_clip(project, accent, shifted)
                    copies.append(new_id)
            return project

        if self.doc.apply("duplicate", duplicated):
            self.doc.select_clips(copies)

    def split_here(self) -> None:
        """Split the selected clips (or every clip) under the playhead or cursor (S, Ctrl+I)."""
        at = self.here()
        project = self.doc.project
        chosen = self.doc.selected_clips or [c.id for t in project.tracks for c in t.clips]
        ids = [
            i for i in chosen if project.find_clip(i)[1].start < at < project.find_clip(i)[1].end
        ]
        if not ids:
            self.doc.message.emit("place the cursor inside a clip to split it", "error")
            return

        def split_all(project: Project) -> Project:
            for clip_id in ids:
                project, _ = edits.split_clip(project, clip_id, at)
            return project

        self.doc.apply("split", split_all)

    def add_marker(self) -> None:
        """Add a marker at the playhead or cursor (M)."""
        at = self.here()
        index = self.doc.apply("add marker", markers.add_marker, at)
        if index is not None:
            m = self.doc.project.markers[index]
            self.doc.message.emit(
                f"marker {m.name} at {axis_text(m.at, self.doc.project.axis)}; "
                "double-click its flag on the ruler to rename it",
                "info",
            )

    def jump(self, direction: int) -> None:
        """Move the playhead and cursor to the next (1) or previous (-1) marker."""
        here = self.view.scene().cursor_u
        ats = [m.at for m in self.doc.project.markers]
        after = [a for a in ats if a > here + 1e-12] if direction > 0 else []
        before = [a for a in ats if a < here - 1e-12] if direction < 0 else []
        if not (after or before):
            self.doc.message.emit("no marker that way", "info")
            return
        self.ruler.place(min(after) if after else max(before))
