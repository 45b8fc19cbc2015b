"""Long imports and exports off the GUI thread, with progress, and Cancel leaves nothing half-done.

An import only reads; the project changes (one undo step) when the read has finished. An export
writes to a temporary file beside the target and renames it into place only if not cancelled.
"""

from __future__ import annotations

import os
import tempfile
import threading
from collections.abc import Callable
from pathlib import Path
from typing import Any

from PySide6.QtCore import QObject, Signal

from timeline.errors import HapticTimelineError
from timeline.files import exporting, importing
from timeline.model import Project


class JobCancelled(HapticTimelineError):
    """The user cancelled a file job."""


class FileJob(QObject):
    """Runs one read or write off the GUI thread; reports progress, result or one error sentence."""

    progress = Signal(float)
    done = Signal(object)
    failed = Signal(str)

    def __init__(self, work: Callable[[Callable[[float], None]], Any]) -> None:
        super().__init__()
        self._work = work
        self._cancel = threading.Event()
        self.thread = threading.Thread(target=self._run, daemon=True)

    def start(self) -> None:
        self.thread.start()

    def cancel(self) -> None:
        """Ask the job to stop at its next progress report."""
        self._cancel.set()

    @property
    def cancelled(self) -> bool:
        return self._cancel.is_set()

    def _report(self, fraction: float) -> None:
        if self._cancel.is_set():
            raise JobCancelled("cancelled")
        self.progress.emit(float(fraction))

    def _run(self) -> None:
        try:
            result = self._work(self._report)
        except JobCancelled:
            self.failed.emit("cancelled; nothing was changed")
            return
        except HapticTimelineError as exc:
            self.failed.emit(str(exc))
            return
        except OSError as exc:
            self.failed.emit(f"{exc.strerror or exc}")
            return
        self.done.emit(result)


def import_job(path: Path) -> FileJob:
    """Read a file (the window places the result on a track when done)."""
    return FileJob(lambda progress: importing.read_file(path, progress=progress))


def export_job(project: Project, path: Path) -> FileJob:
    """Export the project to a temporary file; `finish_export` renames it into place."""

    def work(progress: Callable[[float], None]) -> Path:
        fd, tmp = tempfile.mkstemp(prefix=f".{path.stem}.", suffix=path.suffix, dir=path.parent)
        os.close(fd)
        try:
            exporting.export_project(project, tmp, progress=progress)
        except BaseException:
            Path(tmp).unlink(missing_ok=True)
            raise
        return Path(tmp)

    return FileJob(work)


def finish_export(tmp: Path, path: Path, cancelled: bool) -> None:
    """Rename a finished export onto its target, or remove it if the user cancelled."""
    if cancelled:
        tmp.unlink(missing_ok=True)
    else:
        os.replace(tmp, path)
