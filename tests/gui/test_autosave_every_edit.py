"""Autosave within one edit of a kill; what killed sessions left is removed at the next start."""

from __future__ import annotations

import json
import subprocess

from timeline import edits, generator
from timeline.files import journal, projectfile
from timeline.gui import autosave
from timeline.gui.autosave import Autosaver, recoverable
from timeline.gui.document import Document


def _project():
    p = edits.new_project()
    p, track = edits.add_track(p, "drive")
    p, tile = edits.add_tile(p, generator("sine", 0.1))
    return p, track, tile


def test_each_edit_is_on_disk_once_the_editor_is_idle(tmp_path, monkeypatch, qtbot):
    monkeypatch.setenv("XDG_DATA_HOME", str(tmp_path))
    p, track, tile = _project()
    doc = Document(p)
    saver = Autosaver(doc)
    for i in range(3):
        doc.apply("add clip", edits.add_clip, track, tile, 1.0 + i)
        done = doc.project
        qtbot.waitUntil(lambda done=done: saver.journal.state is done, timeout=2000)
        assert len(journal.replay(saver.path).project.tracks[0].clips) == i + 1
    saver.discard()
    assert not saver.path.exists()


def _dead_pid() -> int:
    child = subprocess.Popen(["true"])
    child.wait()
    return child.pid


def test_the_next_start_removes_partial_and_orphan_session_files(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_DATA_HOME", str(tmp_path))
    folder = autosave.autosave_dir()
    dead = _dead_pid()
    partial = folder / f".session-{dead}.partial-{dead}-x1y2.htl"  # a write killed mid-way
    partial.write_bytes(b"half a project")
    other = _dead_pid()
    orphan = folder / f"session-{other}.json"  # killed between removing the two halves
    orphan.write_text(json.dumps({"pid": other, "path": ""}))
    kept = folder / f"session-{dead}.htl"
    projectfile.save(_project()[0], kept)
    (folder / f"session-{dead}.json").write_text(json.dumps({"pid": dead, "path": ""}))
    found = recoverable()
    assert [r.autosave for r in found] == [kept]  # the complete autosave is still offered
    assert not partial.exists() and not orphan.exists()
