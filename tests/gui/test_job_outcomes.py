"""Every background job ends in exactly one of done, failed or cancelled, and leaves the list;
a failed autosave says so."""

from __future__ import annotations

import errno
import threading
from pathlib import Path

import numpy as np
import pytest
import soundfile
from PySide6.QtCore import QCoreApplication, Qt
from PySide6.QtTest import QTest
from PySide6.QtWidgets import QApplication, QFileDialog

from timeline.files import importing
from timeline.gui import autosave
from timeline.gui.file_jobs import FileJob

IMPORT_KEYS = Qt.KeyboardModifier.ControlModifier | Qt.KeyboardModifier.ShiftModifier


def outcomes_of(job: FileJob) -> list[tuple]:
    """Every outcome signal the job emits, in order (exactly one is expected)."""
    heard: list[tuple] = []
    job.done.connect(lambda result: heard.append(("done", result)))
    job.failed.connect(lambda message: heard.append(("failed", message)))
    job.cancelled.connect(lambda: heard.append(("cancelled",)))
    return heard


def import_by_command(win, monkeypatch, path: Path) -> FileJob:
    """File > Import (Ctrl+Shift+I) with the dialog answering `path`; the job it started."""
    answer = ([str(path)], "")
    monkeypatch.setattr(QFileDialog, "getOpenFileNames", lambda *args, **kwargs: answer)
    QTest.keyClick(win, Qt.Key.Key_I, IMPORT_KEYS)
    [job] = win.jobs
    return job


def ended(job: FileJob) -> None:
    """Wait for the job's thread, then deliver every signal it sent."""
    job.worker_thread.join(20)
    QCoreApplication.processEvents()


@pytest.fixture
def long_wav(tmp_path) -> Path:
    path = tmp_path / "long.wav"
    soundfile.write(path, np.sin(np.linspace(0, 2000, 480_000)).astype("float32"), 48_000)
    return path


def test_an_import_that_raises_a_bug_fails_with_its_type_and_text(
    window, qtbot, monkeypatch, capsys, long_wav
):
    win = window
    before = win.doc.project
    go = threading.Event()

    def broken_reader(path, **options):
        assert go.wait(20)
        raise ValueError("column 3 is not a number\nin row 7")

    monkeypatch.setattr(importing, "read_file", broken_reader)
    job = import_by_command(win, monkeypatch, long_wav)
    heard = outcomes_of(job)
    assert win.messages.cancel.isVisible()
    expected = "Import of long.wav failed: ValueError: column 3 is not a number in row 7"
    with qtbot.waitSignal(job.failed, timeout=10_000) as blocker:
        go.set()
    assert blocker.args == [expected]
    ended(job)
    assert heard == [("failed", expected)]
    assert win.jobs == []
    assert win.messages.history[-1] == (expected, "error")
    assert not win.messages.progress.isVisible() and not win.messages.cancel.isVisible()
    assert win.doc.project is before
    logged = capsys.readouterr().err
    assert "Traceback" in logged and "in broken_reader" in logged


def test_cancelling_an_import_with_the_cancel_button_says_cancelled_not_an_error(
    window, qtbot, monkeypatch, long_wav
):
    win = window
    before = win.doc.project
    first_block, clicked = threading.Event(), threading.Event()
    blocks: list[float] = []
    real_read = importing.read_file

    def read_held_after_the_first_block(path, *, progress=None, **options):
        def report(fraction: float) -> None:
            progress(fraction)  # the job's report: raises once the user has cancelled
            blocks.append(fraction)
            first_block.set()
            assert clicked.wait(20)

        return real_read(path, progress=report, **options)

    monkeypatch.setattr(importing, "read_file", read_held_after_the_first_block)
    win.view.setFocus()
    job = import_by_command(win, monkeypatch, long_wav)
    heard = outcomes_of(job)
    assert first_block.wait(20)
    with qtbot.waitSignal(job.cancelled, timeout=10_000):
        QTest.mouseClick(win.messages.cancel, Qt.MouseButton.LeftButton)
        clicked.set()
    ended(job)
    assert blocks == [65_536 / 480_000]  # the reader stopped at the report after the click
    assert heard == [("cancelled",)]
    assert win.jobs == []
    assert win.messages.history[-1] == ("Import of long.wav cancelled", "info")
    assert not [text for text, level in win.messages.history if level == "error"]
    assert not win.messages.progress.isVisible()
    assert win.doc.project is before
    assert QApplication.focusWidget() is win.view  # not the next widget in the focus chain


def test_a_normal_import_ends_in_done_and_lands_as_one_step(window, qtbot, monkeypatch, long_wav):
    win = window
    steps = len(win.doc.history)
    job = import_by_command(win, monkeypatch, long_wav)
    heard = outcomes_of(job)
    qtbot.waitUntil(lambda: not win.jobs, timeout=10_000)
    assert [name for name, *_ in heard] == ["done"]
    assert win.messages.text == "imported long.wav"
    assert len(win.doc.history) == steps + 1


def test_a_job_ends_in_done_with_its_result(qtbot):
    job = FileJob("Sum", lambda progress: (progress(0.5), 2 + 40)[1])
    heard = outcomes_of(job)
    with qtbot.waitSignal(job.done, timeout=10_000) as blocker:
        job.start()
    assert blocker.args == [42]
    ended(job)
    assert heard == [("done", 42)]


def test_a_cancel_after_the_last_report_still_cancels_and_discards_the_result(qtbot):
    discarded: list[str] = []

    def work(progress) -> str:
        progress(1.0)
        job.cancel()  # the user clicks Cancel as the work returns
        return "temporary file"

    job = FileJob("Export of out.wav", work, discard=discarded.append)
    heard = outcomes_of(job)
    with qtbot.waitSignal(job.cancelled, timeout=10_000):
        job.start()
    ended(job)
    assert heard == [("cancelled",)]
    assert discarded == ["temporary file"]


def test_an_autosave_that_cannot_write_says_so_and_the_next_change_autosaves(
    window, qtbot, monkeypatch
):
    win = window
    real_write = autosave.journal._write_all

    def full_disk(fd, parts):
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(autosave.journal, "_write_all", full_disk)
    win.doc.select_clips([win.ids["c1"]])
    with qtbot.waitSignal(win.autosaver.failed, timeout=10_000) as blocker:
        win.reverse()
    assert blocker.args == ["Autosave failed: No space left on device"]
    assert win.messages.history[-1] == ("Autosave failed: No space left on device", "error")
    assert not win.autosaver.path.exists()
    monkeypatch.setattr(autosave.journal, "_write_all", real_write)
    win.reverse()
    qtbot.waitUntil(win.autosaver.path.exists, timeout=10_000)


def test_a_cancel_clicked_before_the_window_heard_the_end_still_cancels(qtbot):
    discarded: list[str] = []
    job = FileJob("Export of out.wav", lambda progress: "temporary file", discard=discarded.append)
    heard = outcomes_of(job)
    job.start()
    job.worker_thread.join(20)  # the work has returned; its end waits for the GUI thread
    job.cancel()
    QCoreApplication.processEvents()
    assert heard == [("cancelled",)]
    assert discarded == ["temporary file"]
    job.cancel()  # once decided, a late Cancel changes nothing
    QCoreApplication.processEvents()
    assert heard == [("cancelled",)]
