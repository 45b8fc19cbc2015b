"""Long imports and exports off the GUI thread, with progress, and Cancel leaves nothing half-done.

A job ends in exactly one of three signals: `done` (the result), `failed` (one line saying why)
or `cancelled`. An import only reads; the project changes (one undo step) when the read has
finished. An export writes to a temporary file beside the target; the window renames it into
place when the job is done, and a cancelled export removes it.
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
from timeline.files.atomic import file_mode
from timeline.model import Project

from .job_errors import one_line, unexpected

Work = Callable[[Callable[[float], None]], Any]


class JobCancelled(Exception):
    """Raised at a job's next progress report once the user has cancelled it.

    Control flow, not a user error: it is not a HapticTimelineError, so a reader that turns its
    errors into one sentence ("x cannot be imported: ...") lets it pass.
    """


class FileJob(QObject):
    """Runs one read or write off the GUI thread and ends in exactly one of three signals.

    `what` names the job in its messages ("Import of x.wav"). The outcome is decided on the GUI
    thread when the work has ended, so a Cancel clicked while the job is still listed cancels it;
    `discard` tidies up a result that arrived anyway (an export's temporary file).
    """

    progress = Signal(float)
    done = Signal(object)
    failed = Signal(str)
    cancelled = Signal()
    _ended = Signal(object, object)  # the work's result or the exception it raised

    def __init__(self, what: str, work: Work, discard: Callable[[Any], None] | None = None) -> None:
        super().__init__()
        self.what = what
        self._work = work
        self._discard = discard
        self._cancel = threading.Event()
        self._over = False
        self._ended.connect(self._decide)  # queued: runs on the GUI thread
        self.worker_thread = threading.Thread(target=self._run, name=what, daemon=True)

    def start(self) -> None:
        self.worker_thread.start()

    def cancel(self) -> None:
        """Ask the job to stop at its next progress report (no effect once it has ended)."""
        if not self._over:
            self._cancel.set()

    def _report(self, fraction: float) -> None:
        if self._cancel.is_set():
            raise JobCancelled
        self.progress.emit(float(fraction))

    def _run(self) -> None:
        try:
            result = self._work(self._report)
        except Exception as exc:  # noqa: BLE001 - every error ends the job as failed or cancelled
            self._ended.emit(None, exc)
        else:
            self._ended.emit(result, None)

    def _decide(self, result: Any, error: Exception | None) -> None:
        """GUI thread: one outcome, cancelled if the user asked before it was decided."""
        self._over = True
        if self._cancel.is_set():
            try:
                if error is None and self._discard is not None:
                    self._discard(result)
            finally:
                self.cancelled.emit()  # whatever the work raised on its way out
        elif error is not None:
            self.failed.emit(self._message(error))
        else:
            self.done.emit(result)

    def _message(self, exc: Exception) -> str:
        """One line for the message bar: a user error's own sentence, else what failed and why."""
        if isinstance(exc, HapticTimelineError):
            return one_line(str(exc))
        if isinstance(exc, OSError):
            return one_line(f"{self.what} failed: {exc.strerror or exc}")
        return unexpected(self.what, exc)


def import_job(path: Path) -> FileJob:
    """Read a file (the window places the result on a track when done)."""
    from timeline.files import importing  # with the first import, not at start-up

    return FileJob(
        f"Import of {path.name}", lambda progress: importing.read_file(path, progress=progress)
    )


def export_job(project: Project, path: Path, **options: Any) -> FileJob:
    """Export the project to a temporary file; `finish_export` renames it into place.

    `options` are export_project's (the CLI's `--rate` and `--fixed-point`). The file gets the
    permissions the CLI's export gives it: an existing target's, else 0666 less the umask.
    """
    from timeline.files import exporting  # with the first export, not at start-up

    def work(progress: Callable[[float], None]) -> Path:
        fd, tmp = tempfile.mkstemp(prefix=f".{path.stem}.", suffix=path.suffix, dir=path.parent)
        os.close(fd)
        try:
            os.chmod(tmp, file_mode(path))
            exporting.export_project(project, tmp, progress=progress, **options)
        except BaseException:
            Path(tmp).unlink(missing_ok=True)
            raise
        return Path(tmp)

    return FileJob(f"Export of {path.name}", work, discard=lambda tmp: tmp.unlink(missing_ok=True))


def finish_export(tmp: Path, path: Path) -> None:
    """Rename a finished export onto its target."""
    os.replace(tmp, path)
