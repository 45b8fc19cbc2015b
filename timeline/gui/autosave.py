"""Autosave after every change, and recovery of what a crashed session left behind."""

from __future__ import annotations

import json
import os
import threading
from dataclasses import dataclass
from pathlib import Path

import platformdirs
from PySide6.QtCore import QObject, QTimer, Signal

from timeline.errors import HapticTimelineError
from timeline.files import projectfile
from timeline.files.atomic import remove_leftovers, write_atomically
from timeline.model import Project

from .document import Document
from .job_errors import one_line, unexpected

IDLE_MS = 0  # a change is autosaved as soon as the editor returns to its event loop
RETRY_MS = 100  # while a write runs, the next is tried this often


def data_dir() -> Path:
    """The editor's folder in the user data directory (autosaves)."""
    path = Path(platformdirs.user_data_dir("haptic-timeline"))
    path.mkdir(parents=True, exist_ok=True)
    return path


def autosave_dir() -> Path:
    path = data_dir() / "autosave"
    path.mkdir(parents=True, exist_ok=True)
    return path


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


@dataclass(frozen=True)
class Recoverable:
    """An autosave left by a session that did not close: the file and the project it was editing."""

    autosave: Path
    original: Path | None

    def load(self) -> Project:
        return projectfile.load(self.autosave)

    def discard(self) -> None:
        self.autosave.unlink(missing_ok=True)
        self.autosave.with_suffix(".json").unlink(missing_ok=True)


def remove_orphans(folder: Path) -> None:
    """Remove what killed sessions left in the autosave folder besides their autosaves: a
    write's temporary (`.partial`), and a companion (`session-PID.json`) or an autosave whose
    other half is gone (a kill between removing the two)."""
    remove_leftovers(folder)
    for path in [*folder.glob("session-*.json"), *folder.glob("session-*.htl")]:
        other = path.with_suffix(".htl" if path.suffix == ".json" else ".json")
        try:
            pid = int(path.stem.removeprefix("session-"))
        except ValueError:
            continue
        if not other.exists() and pid != os.getpid() and not _alive(pid):
            path.unlink(missing_ok=True)


def recoverable() -> list[Recoverable]:
    """Autosaves of sessions whose process is gone, newest first (orphans removed first)."""
    found = []
    remove_orphans(autosave_dir())
    for meta in sorted(
        autosave_dir().glob("*.json"), key=lambda p: p.stat().st_mtime, reverse=True
    ):
        try:
            info = json.loads(meta.read_text())
            pid = int(info["pid"])
        except (OSError, ValueError, KeyError, TypeError):
            continue
        htl = meta.with_suffix(".htl")
        if pid == os.getpid() or _alive(pid) or not htl.exists():
            continue
        found.append(Recoverable(htl, Path(info["path"]) if info.get("path") else None))
    return found


class Autosaver(QObject):
    """Writes the document to the autosave folder after every change (IDLE_MS), so a kill loses
    at most the changes made while one write ran.

    The write runs on a thread of its own (a project is immutable, so the snapshot taken when the
    editor goes idle cannot change under it): a project holding an hour of audio writes 635 MB of
    samples and syncs them, about a second on a quiet disk, and the editor stays usable meanwhile.
    One write runs at a time; a change during a write is written when it ends (tried every
    RETRY_MS); a state already written is not written again. A write that fails says so
    through `failed` (one line); the next change autosaves again.
    """

    failed = Signal(str)

    def __init__(self, doc: Document, idle_ms: int = IDLE_MS) -> None:
        super().__init__()
        self.doc = doc
        self.timer = QTimer(self)
        self.timer.setSingleShot(True)
        self.timer.setInterval(idle_ms)
        self.timer.timeout.connect(self.save_now)
        doc.changed.connect(lambda _: self.timer.start(idle_ms))
        self.path = autosave_dir() / f"session-{os.getpid()}.htl"
        self.writer: threading.Thread | None = None
        self._writing = threading.Lock()  # held while the files are written or removed
        self._discards = 0  # a write started before the latest discard leaves nothing behind
        self._written: tuple[Project, dict[str, object]] | None = None  # the last state written

    def save_now(self) -> None:
        """Start writing the autosave (only when there are unsaved changes)."""
        if not self.doc.modified:
            self.discard()
            return
        if self.writer is not None and self.writer.is_alive():
            self.timer.start(RETRY_MS)  # the project changed while a write ran: write it after
            return
        meta = {"pid": os.getpid(), "path": str(self.doc.path) if self.doc.path else ""}
        written = self._written
        if written is not None and written[0] is self.doc.project and written[1] == meta:
            return  # this state is the autosave already
        self.writer = threading.Thread(
            target=self._write,
            args=(self.doc.project, meta, self._discards),
            name="autosave",
            daemon=True,
        )
        self.writer.start()

    def _write(self, project: Project, meta: dict[str, object], discards: int) -> None:
        with self._writing:
            if discards != self._discards:
                return
            text = json.dumps(meta).encode("utf-8")  # the companion first: a kill between the two

            def write_meta(tmp: Path) -> None:
                tmp.write_bytes(text)

            try:
                write_atomically(self.path.with_suffix(".json"), write_meta)
                projectfile.save(project, self.path)  # leaves the previous autosave, still found
                self._written = (project, meta)
            except (HapticTimelineError, OSError) as exc:
                reason = exc.strerror if isinstance(exc, OSError) and exc.strerror else exc
                self.failed.emit(one_line(f"Autosave failed: {reason}"))
            except Exception as exc:  # noqa: BLE001 - a bug must not end autosaving unheard
                self.failed.emit(unexpected("Autosave", exc))

    def discard(self) -> None:
        """Remove this session's autosave (after a save or a clean close); a write in progress
        is waited for, and one not yet started will not write."""
        self.timer.stop()
        self._discards += 1
        self._written = None
        with self._writing:
            self.path.unlink(missing_ok=True)
            self.path.with_suffix(".json").unlink(missing_ok=True)
