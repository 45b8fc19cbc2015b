"""Autosave after every change (a journal: timeline.files.journal), and recovery of what a
crashed session left behind."""

from __future__ import annotations

import contextlib
import itertools
import json
import os
import shutil
from dataclasses import dataclass
from pathlib import Path

import platformdirs
from PySide6.QtCore import QObject, QTimer, Signal

from timeline.errors import HapticTimelineError
from timeline.files import journal, projectfile
from timeline.files.atomic import remove_leftovers
from timeline.model import Project

from .document import Document
from .job_errors import one_line, unexpected

BASE_MS = 1000  # a project with no file of its own, clean this long, is written as the base
_SESSIONS = itertools.count()  # a process's sessions (one per window): session-PID-N


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
    """What a session that did not close left: a journal's folder (or an autosave file of an
    older version), and the project file it was editing."""

    autosave: Path
    original: Path | None

    def load(self) -> Project:
        if self.autosave.is_dir():
            return journal.replay(self.autosave).project
        return projectfile.load(self.autosave)

    def discard(self) -> None:
        if self.autosave.is_dir():
            shutil.rmtree(self.autosave, ignore_errors=True)
            return
        self.autosave.unlink(missing_ok=True)
        self.autosave.with_suffix(".json").unlink(missing_ok=True)


def _session_pid(path: Path) -> int | None:
    """The process id in a session's name (session-PID-N, or session-PID.htl of old)."""
    try:
        return int(path.name.removeprefix("session-").split("-")[0].split(".")[0])
    except ValueError:
        return None


def _dead(path: Path) -> bool:
    pid = _session_pid(path)
    return pid is not None and pid != os.getpid() and not _alive(pid)


def remove_orphans(folder: Path) -> None:
    """Remove what killed sessions left in the autosave folder besides what can be recovered: a
    write's temporary (`.partial`), a session folder holding no journal, and of the
    older autosave files a companion (`session-PID.json`) or an autosave whose other half is
    gone (a kill between removing the two)."""
    remove_leftovers(folder)
    for path in folder.glob("session-*"):
        if not _dead(path):
            continue
        if path.is_dir():
            remove_leftovers(path)
            if not any(path.glob("journal-*.log")):  # no edit (a base written, at most)
                shutil.rmtree(path, ignore_errors=True)
        elif path.suffix in (".json", ".htl"):
            other = path.with_suffix(".htl" if path.suffix == ".json" else ".json")
            if not other.exists():
                path.unlink(missing_ok=True)


def _newest(path: Path) -> float:
    """When a session last wrote (its folder's newest file)."""
    files = [*path.iterdir()] if path.is_dir() else [path]
    with contextlib.suppress(OSError):
        return max((f.stat().st_mtime for f in files), default=0.0)
    return 0.0


def recoverable() -> list[Recoverable]:
    """What sessions whose process is gone left, newest first (orphans removed first, and the
    temporaries killed saves left beside each one's project file)."""
    found = []
    folder = autosave_dir()
    remove_orphans(folder)
    for path in folder.glob("session-*"):
        if not _dead(path):
            continue
        if path.is_dir():
            where = journal.read_meta(path).get("path")
            entry = Recoverable(path, Path(where) if isinstance(where, str) and where else None)
        elif path.suffix == ".json":
            try:
                info = json.loads(path.read_text())
                original = Path(info["path"]) if info.get("path") else None
            except (OSError, ValueError, KeyError, TypeError, AttributeError):
                continue
            if not path.with_suffix(".htl").exists():
                continue
            entry = Recoverable(path.with_suffix(".htl"), original)
        else:
            continue
        if entry.original is not None:
            remove_leftovers(entry.original.parent)
        found.append(entry)
    return sorted(found, key=lambda r: _newest(r.autosave), reverse=True)


class Autosaver(QObject):
    """Journals the document at every change, so a kill loses at most the edit being made.

    Each change of the project (an undo and a redo too, each step of a drag) is appended to this
    session's journal as the document announces it, before the view redraws: a few hundred
    bytes for a moved clip, written to the operating system at once (timeline.files.journal);
    a full snapshot is written on a thread now and then. (Written once the editor went idle, a
    window busy redrawing put the journal off: a kill lost 15 edits.) The journal starts from
    the project file the document was opened from or saved to (`on_disk`); a project with no
    file of its own, clean for BASE_MS, is written as the base on a thread, else the first
    record holds it whole (a 20,000-clip project: 0.36 s). Back at the saved state the session's
    journal is removed (a base written for that state is kept, so an undo there costs the next
    edit nothing), and after a save or a clean close all its files. A write that fails says so
    through `failed` (one line); the next change starts a journal anew.
    """

    failed = Signal(str)

    def __init__(self, doc: Document) -> None:
        super().__init__()
        self.doc = doc
        doc.changed.connect(self._changed)
        self.base_timer = QTimer(self)
        self.base_timer.setSingleShot(True)
        self.base_timer.setInterval(BASE_MS)
        self.base_timer.timeout.connect(self._write_base)
        self.path = autosave_dir() / f"session-{os.getpid()}-{next(_SESSIONS)}"
        self.journal = journal.Journal(self.path, failed=self.failed.emit)
        self.offered: list[Recoverable] = []  # discarded at a clean close, once offered
        self._history = doc.history
        self._on_disk: tuple[Project, Path] | None = None
        self._begin()

    def _begin(self) -> None:
        """Start the journal anew: from the saved state, or with unsaved changes, whole."""
        meta = {"pid": os.getpid(), "path": str(self.doc.path) if self.doc.path else ""}
        self.base_timer.stop()
        if self.doc.modified:
            self.journal.start(journal.EMPTY, meta)
            return
        file = self._on_disk[1] if self._on_disk and self._on_disk[0] is self.doc.project else None
        try:
            self.journal.start(self.doc.project, meta, file)
        except OSError:  # the file is gone: the first record writes the project whole
            self.journal.start(self.doc.project, meta)
            file = None
        if file is None:
            self.base_timer.start()

    def _write_base(self) -> None:
        if self.doc.modified or self.journal.state is not self.doc.project:
            return
        try:
            self.journal.write_base()
        except OSError as exc:  # the first record will write the project whole
            self.failed.emit(one_line(f"Autosave failed: {exc.strerror or exc}"))

    def _changed(self, _project: Project) -> None:
        if self.doc.history is not self._history:  # another project: a session of its own
            self._history, self._on_disk = self.doc.history, None
            self._begin()
        self.save_now()

    def on_disk(self, path: Path) -> None:
        """The document's project is what `path` holds now (just opened or saved): the journal
        starts from that file, and the temporaries killed writers left beside it go."""
        self._on_disk = (self.doc.project, Path(path))
        self._begin()
        remove_leftovers(Path(path).parent)  # what a save killed there left

    def save_now(self) -> None:
        """Append the document's state to the journal (only with unsaved changes)."""
        if not self.doc.modified:
            if self.journal.active or self.journal.state is not self.doc.project:
                self._begin()  # back at the saved state: nothing to recover
            return
        if self.journal.state is None:
            self._begin()
        try:
            self.journal.record(self.doc.project)
        except (HapticTimelineError, OSError) as exc:
            reason = exc.strerror if isinstance(exc, OSError) and exc.strerror else exc
            self.failed.emit(one_line(f"Autosave failed: {reason}"))
            self.journal.remove()
        except Exception as exc:  # noqa: BLE001 - a bug must not end autosaving unheard
            self.failed.emit(unexpected("Autosave", exc))
            self.journal.remove()

    def discard(self) -> None:
        """Remove this session's autosave (a snapshot being written is waited for)."""
        self.base_timer.stop()
        self.journal.remove()

    def close(self) -> None:
        """A clean close: this session's files go, and what was offered for recovery."""
        self.discard()
        for entry in self.offered:
            entry.discard()
