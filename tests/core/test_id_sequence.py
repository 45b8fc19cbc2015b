"""IdSequence behaves as the tuple of ids it replaced, and appends leave the old one intact."""

from __future__ import annotations

import json

import pytest
from hypothesis import given
from hypothesis import strategies as st

from timeline import edits
from timeline.files import projectfile
from timeline.model import PaletteTab
from timeline.model.id_sequence import IdSequence
from timeline.tiles import generator

ids = st.lists(st.sampled_from(["tile1", "tile2", "tile10", "a", ""]), max_size=12)


@given(ids, ids)
def test_appending_matches_a_tuple_and_keeps_the_old_sequence(first: list[str], more: list[str]):
    before = IdSequence(first)
    after = before + tuple(more)
    assert before == tuple(first) and list(before) == first
    assert after == tuple(first + more) and len(after) == len(first) + len(more)
    assert hash(after) == hash(tuple(first + more))
    for item in ["tile1", "tile2", "zzz"]:
        assert (item in after) == (item in first + more)
    for i in range(-len(after), len(after)):
        assert after[i] == (first + more)[i]
    assert after[1:3] == tuple(first + more)[1:3]


def test_index_out_of_range_is_an_index_error():
    with pytest.raises(IndexError):
        IdSequence(["a"])[1]
    with pytest.raises(IndexError):
        IdSequence(["a"])[-2]


def test_palette_tab_equality_does_not_depend_on_how_ids_were_given():
    assert PaletteTab("Scratch", "scratch", ("a", "b")) == PaletteTab(
        "Scratch", "scratch", IdSequence(["a"]) + ["b"]
    )
    assert PaletteTab("Scratch", "scratch", ("a", "b")) != PaletteTab("Scratch", "scratch", ("b",))


def test_a_project_built_tile_by_tile_saves_the_same_bytes_and_undo_keeps_old_states():
    project = edits.new_project(templates=False)
    states = [project]
    for i in range(40):
        project, _ = edits.add_tile(project, generator("sine", 1.0, frequency=10.0 + i))
        states.append(project)
    scratch = [tab.tile_ids for tab in states[-1].palette if tab.name == "Scratch"][0]
    assert list(scratch) == [f"tile{i}" for i in range(1, 41)]
    assert [len(s.tab("Scratch").tile_ids) for s in states] == list(range(41))
    text = projectfile.dumps(project)
    again = projectfile.loads(text)
    assert again == project and projectfile.dumps(again) == text
    saved = json.loads(text)["project"]["palette"]
    assert [t["tiles"] for t in saved if t["name"] == "Scratch"] == [list(scratch)]
