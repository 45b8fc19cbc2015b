"""The autosave journal: every edit's record replays to the project, torn and damaged tails end
the replay, snapshots restart it, recordings are written once."""

from __future__ import annotations

import errno

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from timeline import edits, generator
from timeline.edits.history import History
from timeline.edits.markers import add_marker, set_loop
from timeline.errors import ProjectFileError
from timeline.files import journal, projectfile
from timeline.tiles import SampledTile

META = {"pid": 1, "path": ""}


def _project():
    p = edits.new_project()
    p, track = edits.add_track(p, "drive")
    p, tile = edits.add_tile(p, generator("sine", 0.1))
    return p, track, tile


def _edited():
    """A project and the states a few edits of every part of it pass through."""
    p, track, tile = _project()
    states = [p]
    p, clip = edits.add_clip(p, track, tile, 0.5)
    states.append(p)
    p, rec = edits.add_tile(p, SampledTile(np.linspace(-1, 1, 300), 1000.0, "rec"))
    states.append(p)
    p, _ = edits.add_clip(p, track, rec, 1.0)
    states.append(edits.move_clip(p, clip, 2.0))
    states.append(edits.add_clip(states[-1], track, tile, 1.5)[0])  # between two clips
    states.append(edits.set_track(states[-1], track, gain=0.5, mute=True))
    states.append(add_marker(states[-1], 0.25, "hit")[0])
    states.append(set_loop(states[-1], 0.0, 1.5))
    states.append(edits.save_variant(states[-1], "A"))
    p, other = edits.add_track(states[-1], "stiffness")
    states.append(edits.remove_clip(p, clip))
    states.append(edits.remove_track(states[-1], other))
    return states


def _bytes(project) -> str:
    return projectfile.dumps(project)


def _journaled(folder, states, **kwargs) -> journal.Journal:
    j = journal.Journal(folder, **kwargs)
    j.start(states[0], META)
    for state in states[1:]:
        j.record(state)
    j.wait()
    return j


def test_replaying_the_journal_gives_each_edit_of_every_part_of_a_project(tmp_path):
    states = _edited()
    for n in range(2, len(states) + 1):
        folder = tmp_path / f"s{n}"
        _journaled(folder, states[:n])
        replayed = journal.replay(folder)
        assert _bytes(replayed.project) == _bytes(states[n - 1])
        assert replayed.records == n  # the first record holds the opened project whole


def _records(path):
    return list(journal.read_records(path))


def test_a_torn_last_record_is_ignored_at_every_cut(tmp_path):
    states = _edited()[:4]
    folder = tmp_path / "s"
    _journaled(folder, states)
    log = journal.journal_path(folder, 0)
    whole = log.read_bytes()
    ends, at = [], len(journal.MAGIC)
    while at < len(whole):
        length, _crc = journal.HEAD.unpack_from(whole, at)
        at += journal.HEAD.size + length
        ends.append(at)
    assert len(ends) == 5  # the opened project, a clip, a recording and its tile, a move
    for cut in range(ends[-2], len(whole), max(1, (len(whole) - ends[-2]) // 40)):
        log.write_bytes(whole[:cut])
        assert _bytes(journal.replay(folder).project) == _bytes(states[-2])


def test_a_record_that_fails_its_checksum_ends_the_replay_before_it(tmp_path):
    states = _edited()[:5]
    folder = tmp_path / "s"
    _journaled(folder, states)
    log = journal.journal_path(folder, 0)
    data = bytearray(log.read_bytes())
    data[-3] ^= 0x01  # one bit of the last record's JSON
    log.write_bytes(bytes(data))
    assert _bytes(journal.replay(folder).project) == _bytes(states[-2])


def test_snapshots_restart_the_journal_and_recovery_uses_the_newest(tmp_path):
    states = _edited()
    folder = tmp_path / "s"
    _journaled(folder, states, snapshot_records=3)
    names = sorted(p.name for p in folder.iterdir())
    assert names[0].startswith("journal-") and "meta.json" in names
    snapshots = [n for n in names if n.startswith("snapshot-")]
    assert len(snapshots) == 1 and f"journal-{snapshots[0][9:-4]}.log" in names
    assert _bytes(journal.replay(folder).project) == _bytes(states[-1])


def test_a_snapshot_killed_mid_write_leaves_the_journals_before_and_after_it(tmp_path, monkeypatch):
    states = _edited()
    folder = tmp_path / "s"

    def killed(project, path):
        raise OSError(errno.EIO, "killed mid-write")

    monkeypatch.setattr(journal.projectfile, "save", killed)  # no snapshot is ever complete
    _journaled(folder, states, snapshot_records=4)
    names = sorted(p.name for p in folder.iterdir())
    assert names == [f"journal-{g}.log" for g in range(4)] + ["meta.json"]  # none completed
    assert _bytes(journal.replay(folder).project) == _bytes(states[-1])


def test_a_recording_is_written_once_and_an_edit_writes_what_changed(tmp_path):
    p, track, tile = _project()
    data = np.sin(np.arange(100_000) / 50.0)  # 800 kB of samples
    p, rec = edits.add_tile(p, SampledTile(data, 1000.0, "rec"))
    for i in range(100):
        p, _ = edits.add_clip(p, track, tile, 0.25 * i)
    folder = tmp_path / "s"
    j = journal.Journal(folder)
    j.start(p, META)
    q, clip = edits.add_clip(p, track, rec, 200.0)
    j.record(q)
    for i in range(20):
        q = edits.move_clip(q, clip, 201.0 + i)
        j.record(q)
    log = journal.journal_path(folder, 0)
    kinds = [head["kind"] for head, _ in _records(log)]
    assert kinds == ["media"] + ["edit"] * 22  # the samples once, then the project, 21 edits
    assert log.stat().st_size > data.nbytes
    moved = journal.HEAD.size + len(_records(log)[-1][1]) + len(str(_records(log)[-1][0]))
    assert moved < 600  # a moved clip of 101: the clip and its track's fields
    assert _bytes(journal.replay(folder).project) == _bytes(q)


def test_a_journal_started_from_a_file_names_it_and_refuses_it_once_changed(tmp_path):
    p, track, tile = _project()
    path = tmp_path / "design.htl"
    projectfile.save(p, path)
    folder = tmp_path / "s"
    j = journal.Journal(folder)
    j.start(p, META, path)
    q, _ = edits.add_clip(p, track, tile, 0.5)
    j.record(q)
    heads = [h for h, _ in _records(journal.journal_path(folder, 0))]
    assert heads[0]["kind"] == "base" and heads[0]["file"] == str(path)
    assert _bytes(journal.replay(folder).project) == _bytes(q)
    projectfile.save(edits.add_clip(p, track, tile, 3.0)[0], path)
    with pytest.raises(ProjectFileError, match="changed since"):
        journal.replay(folder)


OPS = st.lists(
    st.tuples(
        st.sampled_from(["add", "move", "remove", "gain", "track", "marker", "undo", "redo"]),
        st.integers(0, 50),
        st.floats(0.0, 10.0, allow_nan=False),
    ),
    min_size=1,
    max_size=25,
)


def _step(history: History, op: str, n: int, x: float) -> None:
    p = history.project
    clips = [c for t in p.tracks for c in t.clips]
    if op == "undo":
        history.undo()
    elif op == "redo":
        history.redo()
    elif op == "add" or (op in ("move", "remove", "gain") and not clips):
        track = p.tracks[n % len(p.tracks)].id
        history.do(op, edits.add_clip(p, track, next(iter(p.tiles)), x)[0])
    elif op == "move":
        history.do(op, edits.move_clip(p, clips[n % len(clips)].id, x))
    elif op == "remove":
        history.do(op, edits.remove_clip(p, clips[n % len(clips)].id))
    elif op == "gain":
        history.do(op, edits.set_clip_gain(p, clips[n % len(clips)].id, x))
    elif op == "track":
        history.do(op, edits.add_track(p, "drive")[0])
    else:
        history.do(op, add_marker(p, x)[0])


@settings(max_examples=20, deadline=None)
@given(OPS, st.integers(3, 30))
def test_random_edits_undos_and_redos_replay_to_the_live_project(tmp_path_factory, ops, every):
    folder = tmp_path_factory.mktemp("j") / "s"
    history = History(_project()[0])
    j = journal.Journal(folder, snapshot_records=every)
    j.start(history.project, META)
    for op, n, x in ops:
        _step(history, op, n, x)
        j.record(history.project)
        j.wait()  # snapshots finish in any order relative to edits; here, before the next
    if not (folder / "journal-0.log").exists() and not list(folder.glob("snapshot-*")):
        return  # no edit changed the project (undo at the first step, ...)
    assert _bytes(journal.replay(folder).project) == _bytes(history.project)


def test_a_base_written_ahead_spares_the_first_record_the_whole_project(tmp_path):
    states = _edited()
    base, edited = states[-2], states[-1]
    folder = tmp_path / "s"
    j = journal.Journal(folder)
    j.start(base, META)
    j.write_base()
    j.wait()
    assert sorted(p.name for p in folder.iterdir()) == ["meta.json", "snapshot-0.htl"]
    with pytest.raises(ProjectFileError, match="holds no edit"):
        journal.replay(folder)  # the base alone is nothing to recover
    j.record(edited)
    heads = [h for h, _ in _records(journal.journal_path(folder, 0))]
    assert [h["kind"] for h in heads] == ["base", "edit"] and heads[0]["snapshot"] == 0
    assert "tiles" not in heads[1]["change"]  # only the track removed
    assert _bytes(journal.replay(folder).project) == _bytes(edited)
    journal.snapshot_path(folder, 0).unlink()
    with pytest.raises(ProjectFileError, match="first snapshot is missing"):
        journal.replay(folder)


def test_starting_again_at_the_written_base_keeps_it(tmp_path):
    """Back at the state the base snapshot holds (an undo to it), the session starts anew
    without deleting that snapshot: the next edit's first record names it instead of holding
    the project whole (0.4-0.7 s on the GUI thread at 20,000 clips). Another state does not
    keep it."""
    states = _edited()
    base, edited, other = states[-3], states[-2], states[-1]
    folder = tmp_path / "s"
    j = journal.Journal(folder)
    j.start(base, META)
    j.write_base()
    j.wait()
    snapshot = journal.snapshot_path(folder, 0)
    written = snapshot.read_bytes()
    j.record(edited)
    j.start(base, META)  # undone back to the base
    assert sorted(p.name for p in folder.iterdir()) == ["meta.json", "snapshot-0.htl"]
    assert snapshot.read_bytes() == written
    j.record(other)
    heads = [h for h, _ in _records(journal.journal_path(folder, 0))]
    assert [h["kind"] for h in heads] == ["base", "edit"] and heads[0]["snapshot"] == 0
    assert _bytes(journal.replay(folder).project) == _bytes(other)
    j.start(edited, META)  # a state the snapshot does not hold: it goes
    assert not folder.exists()
    j.record(other)
    heads = [h for h, _ in _records(journal.journal_path(folder, 0))]
    assert [h["kind"] for h in heads] == ["media", "edit", "edit"]  # the project whole, then it
    assert _bytes(journal.replay(folder).project) == _bytes(other)
