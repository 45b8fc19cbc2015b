"""A malformed project file is refused with one sentence that names the field where it is
wrong (the full sentence, not a fragment), and a saved file's bytes load as the project."""

from __future__ import annotations

import json
from collections import OrderedDict
from collections.abc import Callable

import numpy as np
import pytest

from timeline import edits
from timeline.errors import FieldError, ProjectFileError
from timeline.files import project_fields as fields
from timeline.files import projectfile
from timeline.model import Project
from timeline.tiles import SampledTile, generator

INF = "@inf@"  # written as the bare literal 1e999, which json reads as inf
SPLINE = {"type": "spline", "name": "sp", "duration": 0.01, "method": "linear"}


def _project() -> Project:
    project = edits.new_project(rate=1000.0, templates=False)
    project, track = edits.add_track(project, "drive")
    project, tile = edits.add_tile(project, SampledTile(np.array([0.5, -0.25]), 1000.0, "s"))
    project, _ = edits.add_tile(project, generator("sine", 0.01, frequency=100.0))
    project, _ = edits.add_clip(project, track, tile, 0.0)
    return project


def _tiles(doc: dict) -> dict:
    return doc["project"]["tiles"]


def _track(doc: dict) -> dict:
    return doc["project"]["tracks"][0]


def _clip(doc: dict) -> dict:
    return _track(doc)["clips"][0]


CASES: dict[str, tuple[Callable[[dict], object], str]] = {
    "media key a number": (
        lambda d: _tiles(d)["tile2"].update(media=5),
        "project tile 'tile2'.media should be text",
    ),
    "sampled rate zero": (
        lambda d: _tiles(d)["tile2"].update(rate=0),
        "project tile 'tile2'.rate should be above zero, not 0",
    ),
    "sampled rate negative": (
        lambda d: _tiles(d)["tile2"].update(rate=-1000.0),
        "project tile 'tile2'.rate should be above zero, not -1000",
    ),
    "spline point of three": (
        lambda d: _tiles(d).update(tile3={**SPLINE, "points": [[0.0, 0.0, 1.0]]}),
        "project tile 'tile3'.points should be [time, value] pairs",
    ),
    "spline point as text": (
        lambda d: _tiles(d).update(tile3={**SPLINE, "points": ["ab"]}),
        "project tile 'tile3'.points should be [time, value] pairs",
    ),
    "generator params a list": (
        lambda d: _tiles(d)["tile3"].update(params=[1.0]),
        "project tile 'tile3'.params should be an object",
    ),
    "negative full scale": (
        lambda d: _track(d).update(full_scale=-1.0),
        "project.tracks[0].full_scale should be above zero, not -1",
    ),
    "mute as text": (
        lambda d: _track(d).update(mute="yes"),
        "project.tracks[0].mute should be true or false",
    ),
    "infinite clip gain": (
        lambda d: _clip(d).update(gain=INF),
        "project.tracks[0].clips[0].gain should be a finite number, not inf",
    ),
    "fade length as text": (
        lambda d: _clip(d).update(fade_in={"length": "0.1", "shape": "linear"}),
        "project.tracks[0].clips[0].fade_in.length should be a number, not text",
    ),
    "marker name a number": (
        lambda d: d["project"].update(markers=[{"name": 5, "at": 0.0}]),
        "project.markers[0].name should be text",
    ),
    "no schema": (lambda d: d.pop("schema"), "its schema version is missing"),
    "media a list": (lambda d: d.update(media=[]), "the file.media should be an object"),
    "tiles a list": (lambda d: d["project"].update(tiles=[]), "project.tiles should be an object"),
    "variants an object": (
        lambda d: d["project"].update(variants={}),
        "project.variants should be a list",
    ),
    "palette tab name a number": (
        lambda d: d["project"]["palette"][0].update(name=5),
        "palette tab.name should be text",
    ),
    "loop of one value": (
        lambda d: d["project"].update(loop=[0.5]),
        "project.loop should be [start, stop] or null",
    ),
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_a_malformed_field_is_named_in_full(case: str) -> None:
    change, message = CASES[case]
    doc = json.loads(projectfile.dumps(_project()))
    change(doc)
    text = json.dumps(doc).replace(f'"{INF}"', "1e999")
    with pytest.raises(ProjectFileError) as info:
        projectfile.loads(text, "bad.htl")
    assert str(info.value) == f"bad.htl cannot be opened: {message}"


def test_a_file_that_cannot_be_opened_is_named_by_its_path(tmp_path) -> None:
    doc = json.loads(projectfile.dumps(_project()))
    _track(doc).update(mute="yes")
    path = tmp_path / "bad.htl"
    path.write_text(json.dumps(doc))
    with pytest.raises(ProjectFileError) as info:
        projectfile.load(path)
    assert (
        str(info.value)
        == f"{path} cannot be opened: project.tracks[0].mute should be true or false"
    )


def test_a_loop_that_ends_before_it_starts_is_refused_at_project_loop() -> None:
    doc = json.loads(projectfile.dumps(_project()))
    doc["project"]["loop"] = [0.5, 0.1]
    with pytest.raises(ProjectFileError) as info:
        projectfile.loads(json.dumps(doc))
    assert str(info.value).startswith("the project cannot be opened: project.loop: ")


def test_a_plain_fade_reads_as_the_fade_it_holds() -> None:
    project = _project()
    clip = project.tracks[0].clips[0]
    project = edits.set_fade(project, clip.id, "in", 0.001, "s-curve")
    loaded = projectfile.loads(projectfile.dumps(project))
    assert loaded.tracks[0].clips[0].fade_in == project.tracks[0].clips[0].fade_in
    assert loaded == project


def test_a_saved_files_bytes_load_as_the_project(tmp_path) -> None:
    project = _project()
    path = tmp_path / "p.htl"
    projectfile.save(project, path)
    data = path.read_bytes()
    assert projectfile.loads(data) == project
    assert projectfile.loads(data).tile(project.tracks[0].clips[0].tile_id).data.tolist() == [
        0.5,
        -0.25,
    ]


def test_the_field_helpers_name_where_a_value_is_wrong() -> None:
    assert fields.get(OrderedDict(name="x"), "name", str, "w") == "x"  # any dict will do
    with pytest.raises(FieldError, match=r"^entry should be an object$"):
        fields.number(5, "rate", "entry")
    with pytest.raises(FieldError, match=r"^x should be a finite number, not inf$"):
        fields.as_number(float("inf"), "x")
    with pytest.raises(FieldError, match=r"^t.mute should be true or false$"):
        fields.flag({"mute": 1}, "mute", "t")
