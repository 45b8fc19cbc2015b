"""Markers and the loop region: edits, the file round trip and schema 1 files."""

from __future__ import annotations

import json
import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

from timeline import edits
from timeline.edits import markers
from timeline.errors import EditError, ProjectFileError
from timeline.files import projectfile
from timeline.model.markers import LoopRegion, Marker


def test_markers_stay_sorted_and_get_free_names():
    p = edits.new_project(templates=False)
    p, i = markers.add_marker(p, 2.0)
    p, j = markers.add_marker(p, 0.5)
    p, k = markers.add_marker(p, 1.0, "hit")
    assert [(m.name, m.at) for m in p.markers] == [("M2", 0.5), ("hit", 1.0), ("M1", 2.0)]
    assert (i, j, k) == (0, 0, 1)
    p = markers.move_marker(p, 0, 3.0)
    assert [m.name for m in p.markers] == ["hit", "M1", "M2"]
    p = markers.rename_marker(p, 0, " chorus ")
    assert p.markers[0] == Marker("chorus", 1.0)
    p = markers.remove_marker(p, 1)
    assert [m.name for m in p.markers] == ["chorus", "M2"]
    assert markers.next_marker_name(p) == "M1"
    with pytest.raises(EditError, match="no marker 3"):
        markers.remove_marker(p, 2)
    with pytest.raises(EditError, match="finite"):
        markers.add_marker(p, math.nan)
    with pytest.raises(EditError, match="needs a name"):
        markers.rename_marker(p, 0, "  ")


def test_loop_region_is_ordered_and_clears():
    p = edits.new_project(templates=False)
    p = markers.set_loop(p, 1.5, 0.25)
    assert p.loop == LoopRegion(0.25, 1.5)
    assert markers.set_loop(p, 1.0, 1.0).loop is None
    assert markers.set_loop(p, None).loop is None
    with pytest.raises(EditError, match="end after"):
        LoopRegion(1.0, 1.0)


def test_markers_and_loop_survive_a_save(tmp_path):
    p = edits.new_project("position", templates=False)
    p, _ = markers.add_marker(p, math.radians(110), "Lo")
    p = markers.set_loop(p, 0.1, 0.7)
    projectfile.save(p, tmp_path / "m.htl")
    again = projectfile.load(tmp_path / "m.htl")
    assert again == p
    body = json.loads((tmp_path / "m.htl").read_text())["project"]
    assert body["markers"] == [{"name": "Lo", "at": math.radians(110)}]
    assert body["loop"] == [0.1, 0.7]


@pytest.mark.parametrize("schema", [1, 2])
def test_an_older_file_opens_without_markers(tmp_path, schema):
    p = edits.new_project(templates=False)
    doc = projectfile.to_json(p)
    del doc["project"]["markers"], doc["project"]["loop"]
    doc["schema"] = schema
    (tmp_path / "old.htl").write_text(json.dumps(doc))
    again = projectfile.load(tmp_path / "old.htl")
    assert again.markers == () and again.loop is None


@pytest.mark.parametrize(
    ("markers_json", "loop", "message"),
    [
        ([{"name": "a", "at": "x"}], None, "markers"),
        ([{"name": "", "at": 1.0}], None, "needs a name"),
        (["a"], None, "should be an object"),
        ([], [2.0, 1.0], "end after"),
        ([], [1.0], r"\[start, stop\]"),
        ([], [1.0, "inf"], "loop"),
    ],
)
def test_bad_markers_are_one_sentence(tmp_path, markers_json, loop, message):
    doc = projectfile.to_json(edits.new_project(templates=False))
    doc["project"]["markers"], doc["project"]["loop"] = markers_json, loop
    (tmp_path / "bad.htl").write_text(json.dumps(doc))
    with pytest.raises(ProjectFileError, match=message):
        projectfile.load(tmp_path / "bad.htl")


@given(st.lists(st.tuples(st.floats(-10, 10), st.sampled_from(["a", "b", "Lo"])), max_size=8))
def test_any_markers_round_trip_sorted(entries):
    p = edits.new_project(templates=False)
    for at, name in entries:
        p, _ = markers.add_marker(p, at, name)
    ats = [m.at for m in p.markers]
    assert ats == sorted(ats) and min(ats, default=0.0) >= 0.0
    assert projectfile.loads(projectfile.dumps(p)) == p
