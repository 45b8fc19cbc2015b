"""The open document: the undo history, the file path and the selection, with change signals.

The view only requests changes through `apply`; an edit that refuses (EditError) leaves the
project untouched and reports one sentence to the message bar.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

from PySide6.QtCore import QObject, Signal

from timeline.edits.history import History
from timeline.errors import HapticTimelineError
from timeline.model import Project


class Document(QObject):
    """One project being edited: history (undo/redo, modified flag), path and selection."""

    changed = Signal(object)  # the new Project
    selection_changed = Signal()
    message = Signal(str, str)  # text, level ("info" or "error")
    outcome = Signal(str)  # a step of the history taken: held against routine status
    modified_changed = Signal(bool)

    def __init__(self, project: Project, path: Path | None = None) -> None:
        super().__init__()
        self.history = History(project)
        self.path = path
        self.selected_clips: list[str] = []
        self.selected_tile: str | None = None
        self.selected_marker: int | None = None  # index in the project's sorted markers
        self.selected_track: str | None = None
        self.inspected = "clip"  # what was selected last: "clip", "marker" or "track"
        self._announced: object = None  # merge key of the drag last announced

    @property
    def project(self) -> Project:
        return self.history.project

    @property
    def modified(self) -> bool:
        return self.history.modified

    def apply(
        self,
        label: str,
        edit: Callable[..., Any],
        *args: Any,
        merge_key: object = None,
        base: Project | None = None,
        **kwargs: Any,
    ) -> Any:
        """Run an edit on the project (or on `base`, a drag's starting state) and record it.

        Returns the edit's extra result (a new id) or True; None when the edit was refused.
        """
        try:
            result = edit(self.project if base is None else base, *args, **kwargs)
        except HapticTimelineError as exc:
            self.message.emit(str(exc), "error")
            return None
        project, extra = result if isinstance(result, tuple) else (result, True)
        self.replace(label, project, merge_key)
        return extra

    def replace(self, label: str, project: Project, merge_key: object = None) -> None:
        """Record a project computed elsewhere (an import) as one step."""
        self.history.do(label, project, merge_key)
        if merge_key is None or merge_key is not self._announced:
            self._announced = merge_key
            self.message.emit(f"{label} (Ctrl+Z undoes)", "info")
        self._prune_selection()
        self._emit_changed()

    def undo(self) -> None:
        """Step back one action."""
        if not self.history.can_undo:
            self.message.emit("nothing to undo", "info")
            return
        name = self.history.undo_name
        self.history.undo()
        self.outcome.emit(f"undid {name}")
        self._prune_selection()
        self._emit_changed()

    def redo(self) -> None:
        """Step forward one action."""
        if not self.history.can_redo:
            self.message.emit("nothing to redo", "info")
            return
        self.history.redo()
        self.outcome.emit(f"redid {self.history.undo_name}")
        self._prune_selection()
        self._emit_changed()

    def go_to(self, index: int) -> None:
        """Jump to a step of the history (Edit > History)."""
        if index == self.history.index:
            return
        way = "back" if index < self.history.index else "forward"
        self.history.go_to(index)
        self.outcome.emit(f"{way} to step {index}: {self.history.names[index]}")
        self._prune_selection()
        self._emit_changed()

    def reset(self, project: Project, path: Path | None) -> None:
        """Start over on another project (a fresh history, nothing selected)."""
        self.history = History(project)
        self.path = path
        self.selected_marker = self.selected_track = None
        self.select_clips([])
        self.select_tile(None)
        self._emit_changed()

    def mark_saved(self, path: Path) -> None:
        """Remember the file the project was saved to, and that it is clean."""
        self.path = path
        self.history.mark_clean()
        self._emit_modified()

    def select_clips(self, clip_ids: list[str]) -> None:
        """Replace the clip selection."""
        clip_ids = list(dict.fromkeys(clip_ids))
        inspected = "clip" if clip_ids else self.inspected
        if clip_ids != self.selected_clips or inspected != self.inspected:
            self.selected_clips, self.inspected = clip_ids, inspected
            self.selection_changed.emit()

    def select_tile(self, tile_id: str | None) -> None:
        """Choose the tile shown in the waveform editor."""
        if tile_id != self.selected_tile:
            self.selected_tile = tile_id
            self.selection_changed.emit()

    def select_marker(self, index: int | None) -> None:
        """Choose the marker the inspector shows (an index into the sorted markers)."""
        if (index, "marker") != (self.selected_marker, self.inspected):
            self.selected_marker, self.inspected = index, "marker"
            self.selection_changed.emit()

    def select_track(self, track_id: str | None) -> None:
        """Choose the track the inspector shows."""
        if (track_id, "track") != (self.selected_track, self.inspected):
            self.selected_track, self.inspected = track_id, "track"
            self.selection_changed.emit()

    def _prune_selection(self) -> None:
        project = self.project
        kept = [c for c in self.selected_clips if any(c in t.clips_by_id for t in project.tracks)]
        tile = self.selected_tile if self.selected_tile in project.tiles else None
        marker = self.selected_marker
        marker = marker if marker is not None and marker < len(project.markers) else None
        track = self.selected_track
        track = track if any(t.id == track for t in project.tracks) else None
        before = (
            self.selected_clips,
            self.selected_tile,
            self.selected_marker,
            self.selected_track,
        )
        if (kept, tile, marker, track) != before:
            self.selected_clips, self.selected_tile, self.selected_marker = kept, tile, marker
            self.selected_track = track
            self.selection_changed.emit()

    def _emit_changed(self) -> None:
        self.changed.emit(self.project)
        self._emit_modified()

    def _emit_modified(self) -> None:
        self.modified_changed.emit(self.modified)
