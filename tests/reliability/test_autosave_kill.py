"""SIGKILL while editing: recovery in another process holds every edit but at most the one in
flight, snapshots being written included, and leaves nothing behind.

A child process opens a multi-MB project (2,000 clips and an 8 MB recording, made by code),
adds a clip every 5 ms with an undo every fourth step, and snapshots every 10 records, so the
kills land while a snapshot is written as well as between; the loop is
timeline/bench/autosave_journal.py's (its `bench autosave` table is in docs/reliability.md).
"""

from __future__ import annotations

import pytest

from timeline.bench.autosave_journal import kill_loop

from .conftest import count

KILLS = 30


def _check(kills) -> None:
    for kill in kills:
        assert kill.applied > 0  # the child was editing when killed
        assert kill.lost <= 1, kill  # at most the edit in flight
        assert kill.left == []  # the recovered session, and every temporary, is gone


def test_a_kill_while_editing_loses_at_most_the_edit_in_flight():
    _check(kill_loop(count(1), seed=5, window=False, clips=2_000, samples=1_000_000))


@pytest.mark.heavy
def test_kills_of_the_editor_window_in_a_loop_lose_at_most_one_edit_each():
    kills = kill_loop(count(KILLS), seed=6, window=True, clips=2_000, samples=1_000_000)
    _check(kills)
    assert any(k.during_snapshot for k in kills)  # some kills landed mid-snapshot
