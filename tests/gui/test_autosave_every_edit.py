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


def test_a_dead_session_is_offered_and_removed_at_the_next_clean_close(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_DATA_HOME", str(tmp_path))
    folder = autosave.autosave_dir()
    p, track, tile = _project()
    edited, _ = edits.add_clip(p, track, tile, 1.5)
    dead = _dead_pid()
    session = folder / f"session-{dead}-0"
    killed = journal.Journal(session)
    killed.start(p, {"pid": dead, "path": ""})
    killed.record(edited)
    partial = session / f".snapshot-1.partial-{dead}-ab12.htl"  # a snapshot killed mid-write
    partial.write_bytes(b"half a project")
    empty = folder / f"session-{_dead_pid()}-0"  # killed before its first record
    empty.mkdir()
    (empty / "meta.json").write_text("{}")
    doc = Document(p)
    saver = Autosaver(doc)
    doc.apply("add clip", edits.add_clip, track, tile, 2.5)  # this live session is not offered
    found = recoverable()
    assert [r.autosave for r in found] == [session]
    assert not partial.exists() and not empty.exists()
    assert found[0].load() == edited
    saver.offered = found
    saver.close()
    assert list(folder.iterdir()) == []


def test_the_journal_starts_from_the_file_and_goes_back_at_the_saved_state(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_DATA_HOME", str(tmp_path))
    p, track, tile = _project()
    path = tmp_path / "design.htl"
    projectfile.save(p, path)
    doc = Document(p, path)
    saver = Autosaver(doc)
    saver.on_disk(path)
    doc.apply("add clip", edits.add_clip, track, tile, 1.0)
    heads = [h for h, _ in journal.read_records(journal.journal_path(saver.path, 0))]
    assert [h["kind"] for h in heads] == ["base", "edit"] and heads[0]["file"] == str(path)
    doc.undo()  # the saved state: nothing to recover
    assert not saver.path.exists()
    doc.redo()
    assert journal.replay(saver.path).project == doc.project
    saver.discard()


def test_an_undo_back_to_a_never_saved_project_keeps_its_base(tmp_path, monkeypatch, qtbot):
    """A project with no file of its own gets its base written on a thread once clean; an undo
    back to that state starts the session anew but keeps the base, so the next edit's first
    record names it (at 20,000 clips the whole project took 0.4-0.7 s on the GUI thread)."""
    monkeypatch.setenv("XDG_DATA_HOME", str(tmp_path))
    p, track, tile = _project()
    doc = Document(p)
    saver = Autosaver(doc)
    base = journal.snapshot_path(saver.path, 0)
    saver.base_timer.setInterval(0)
    saver.base_timer.start()
    qtbot.waitUntil(lambda: base.exists() and not saver.journal.writing, timeout=5000)
    doc.apply("add clip", edits.add_clip, track, tile, 1.0)
    doc.undo()  # the clean state again: the journal goes, its base stays
    assert sorted(f.name for f in saver.path.iterdir()) == ["meta.json", "snapshot-0.htl"]
    assert projectfile.load(base) == p
    doc.apply("add clip", edits.add_clip, track, tile, 2.0)
    heads = [h for h, _ in journal.read_records(journal.journal_path(saver.path, 0))]
    assert [h["kind"] for h in heads] == ["base", "edit"] and heads[0]["snapshot"] == 0
    assert journal.replay(saver.path).project == doc.project
    saver.discard()
    assert not saver.path.exists()
