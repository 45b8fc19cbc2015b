"""Autosave and crash recovery (a killed child process), background import/export with cancel."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
import threading
import time
from pathlib import Path

import numpy as np
import pytest
import soundfile

from timeline.errors import ProjectFileError
from timeline.files import journal
from timeline.gui import autosave

CHILD = textwrap.dedent(
    """
    import os, sys
    os.environ["QT_QPA_PLATFORM"] = "offscreen"
    from PySide6.QtWidgets import QApplication
    app = QApplication([])
    from timeline.gui.main_window import MainWindow
    from timeline import edits
    win = MainWindow()
    track = win.doc.project.tracks[0].id
    tile = win.doc.project.tab("Templates").tile_ids[0]
    win.doc.apply("add clip", edits.add_clip, track, tile, 1.25)
    print("edited", flush=True)
    sys.exit(app.exec())
    """
)


def _journaled(folder: Path) -> bool:
    """Whether a session in the autosave folder holds an edit."""
    for session in folder.glob("session-*"):
        try:
            journal.replay(session)
        except (ProjectFileError, OSError):
            continue
        return True
    return False


def test_autosave_survives_a_killed_process_and_is_offered(window, data_home, tmp_path):
    env = {**os.environ, "XDG_DATA_HOME": str(data_home)}
    child = subprocess.Popen([sys.executable, "-c", CHILD], env=env, stdout=subprocess.PIPE)
    try:
        assert child.stdout.readline().strip() == b"edited"
        folder = data_home / "haptic-timeline" / "autosave"
        deadline = time.monotonic() + 20
        while not _journaled(folder) and time.monotonic() < deadline:
            time.sleep(0.05)
    finally:
        child.send_signal(signal.SIGKILL)
        child.wait()
    found = window.offer_recovery()
    assert len(found) == 1
    assert window.messages.action.isVisible() or window.messages.action.text() == "Recover"
    window.messages.action.click()
    clips = [c for t in window.doc.project.tracks for c in t.clips]
    assert [c.start for c in clips] == [1.25]
    assert window.doc.modified
    assert autosave.recoverable() == []


def test_idle_autosave_writes_then_a_save_removes_it(window, qtbot, tmp_path):
    window.doc.select_clips([window.ids["c1"]])
    window.reverse()
    qtbot.waitUntil(window.autosaver.path.exists, timeout=3000)
    window.save_to(tmp_path / "kept.htl")
    assert not window.autosaver.path.exists()


@pytest.fixture
def long_wav(tmp_path) -> Path:
    path = tmp_path / "long.wav"
    soundfile.write(path, np.sin(np.linspace(0, 2000, 480_000)).astype("float32"), 48_000)
    return path


def test_import_in_the_background_lands_as_one_step(window, qtbot, long_wav):
    before = len(window.doc.history)
    window.import_files([long_wav], window.ids["t3"], 4.0)
    qtbot.waitUntil(lambda: not window.jobs, timeout=10_000)
    clips = window.doc.project.track(window.ids["t3"]).clips
    assert [round(c.start, 6) for c in clips] == [4.0]
    assert len(window.doc.history) == before + 1


def test_cancelled_import_changes_nothing(window, qtbot, long_wav):
    before = window.doc.project
    window.import_files([long_wav], window.ids["t1"], 0.0)
    window.messages.cancel.click()
    qtbot.waitUntil(lambda: not window.jobs, timeout=10_000)
    assert window.doc.project == before


def test_export_writes_only_when_finished_and_cancel_leaves_no_file(window, qtbot, tmp_path):
    target = tmp_path / "out.wav"
    window.export_to(target)
    qtbot.waitUntil(lambda: not window.jobs, timeout=10_000)
    assert target.exists()
    target2 = tmp_path / "out2.wav"
    job = window.export_to(target2)
    job.cancel()
    qtbot.waitUntil(lambda: not window.jobs, timeout=10_000)
    assert not target2.exists()
    assert sorted(p.name for p in tmp_path.iterdir() if p.name.startswith(".out2")) == []


def _held_snapshot(monkeypatch):
    """projectfile.save as the journal's snapshot calls it, held until the returned event is set."""
    started, release = threading.Event(), threading.Event()
    real_save = journal.projectfile.save

    def held(project, path):
        started.set()
        assert release.wait(20)
        real_save(project, path)

    monkeypatch.setattr(journal.projectfile, "save", held)
    return started, release


def test_a_snapshot_writes_on_its_own_thread_while_edits_are_journaled(window, monkeypatch):
    started, release = _held_snapshot(monkeypatch)
    saver = window.autosaver
    saver.base_timer.stop()  # no base of the clean project written meanwhile
    saver.journal.wait()
    saver.journal.snapshot_records = 1  # the first record starts a snapshot
    window.doc.select_clips([window.ids["c1"]])
    window.reverse()
    saver.save_now()
    assert started.wait(10) and saver.journal.writing  # the snapshot waits; the editor does not
    window.reverse()  # an edit while the snapshot runs is journaled at once
    saver.save_now()
    assert journal.replay(saver.path).project == window.doc.project
    assert window.doc.project.find_clip(window.ids["c1"])[1].reverse is False
    release.set()
    saver.journal.wait()
    assert sorted(p.name for p in saver.path.iterdir()) == [
        "journal-1.log",  # the edits after the snapshot; journal 0 is gone
        "meta.json",
        "snapshot-1.htl",
    ]
    assert journal.replay(saver.path).project == window.doc.project


def test_a_discard_waits_for_the_snapshot_and_leaves_no_autosave(window, monkeypatch):
    started, release = _held_snapshot(monkeypatch)
    saver = window.autosaver
    saver.base_timer.stop()  # no base of the clean project written meanwhile
    saver.journal.wait()
    saver.journal.snapshot_records = 1
    window.doc.select_clips([window.ids["c1"]])
    window.reverse()
    saver.save_now()
    assert started.wait(10)
    threading.Timer(0.2, release.set).start()  # the write finishes while discard waits for it
    saver.discard()
    assert not saver.journal.writing
    assert not saver.path.exists()
