"""Copy, cut and paste of clips through the system clipboard (Ctrl+C, Ctrl+X, Ctrl+V).

The clipboard gets the project's own mime type and the same snippet as JSON text, so clips move
between tracks, between open projects (and editor processes), and into a script.
"""

from __future__ import annotations

from collections.abc import Callable

from PySide6.QtCore import QMimeData
from PySide6.QtGui import QGuiApplication

from timeline import edits
from timeline.edits.vibration import with_emphasis
from timeline.errors import HapticTimelineError
from timeline.files import clipboard
from timeline.model import Project

from .document import Document


def put(clips: Project) -> None:
    """Place a snippet on the system clipboard in both forms."""
    text = clipboard.to_text(clips)
    mime = QMimeData()
    mime.setData(clipboard.MIME, text.encode())
    mime.setText(text)
    QGuiApplication.clipboard().setMimeData(mime)


def taken() -> Project:
    """The snippet on the system clipboard (our mime type, else its text)."""
    mime = QGuiApplication.clipboard().mimeData()
    if mime is not None and mime.hasFormat(clipboard.MIME):
        return clipboard.from_text(bytes(mime.data(clipboard.MIME).data()))
    text = mime.text() if mime is not None else ""
    if not text.strip():
        raise HapticTimelineError("the clipboard is empty")
    return clipboard.from_text(text)


class ClipClipboard:
    """The editor's copy, cut and paste; `where` says where a paste starts."""

    def __init__(self, doc: Document, where: Callable[[], float]) -> None:
        self.doc, self.where = doc, where

    def chosen(self) -> list[str]:
        """What copy and cut take: the selected clips, a design with its emphasis."""
        return with_emphasis(self.doc.project, self.doc.selected_clips)

    def copy(self) -> bool:
        """Copy the selected clips."""
        try:
            clips = clipboard.snippet(self.doc.project, self.chosen())
        except HapticTimelineError as exc:
            self.doc.message.emit(str(exc), "error")
            return False
        put(clips)
        count = sum(len(t.clips) for t in clips.tracks)
        self.doc.message.emit(f"copied {count} clip{'s' * (count != 1)}", "info")
        return True

    def cut(self) -> None:
        """Copy the selected clips and remove them (one undo step)."""
        ids = self.chosen()
        if self.copy():
            self.doc.apply("cut", edits.remove_clips, ids)

    def paste(self) -> None:
        """Paste at the playhead or cursor, on the selected clip's track (or one of the kind)."""
        try:
            clips = taken()
        except HapticTimelineError as exc:
            self.doc.message.emit(f"nothing to paste: {exc}", "error")
            return
        selected = self.doc.selected_clips
        track = self.doc.project.find_clip(selected[0])[0].id if selected else None
        new_ids = self.doc.apply("paste", clipboard.paste, clips, self.where(), track)
        if new_ids:
            self.doc.select_clips(new_ids)
