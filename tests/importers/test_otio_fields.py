"""Our fields in an OTIO file read strictly: words as flags, text as numbers, or one sentence."""

from __future__ import annotations

import base64
import copy
import json

import numpy as np
import pytest

from importers.otio import _read
from timeline import edits
from timeline.errors import FormatError
from timeline.files import exporting, importing, projectfile
from timeline.tiles import generator


@pytest.fixture(scope="module")
def exported(tmp_path_factory):
    """A one-clip design as an .otio, as JSON: track 0 is the drive track, item 1 its clip."""
    folder = tmp_path_factory.mktemp("otio")
    p = edits.new_project(templates=False)
    p, track = edits.add_track(p, "drive", "D")
    p, tile = edits.add_tile(p, generator("sine", 0.5))
    p, _ = edits.add_clip(p, track, tile, 0.1)
    exporting.export_project(p, folder / "base.otio")
    return json.loads((folder / "base.otio").read_text())


def _write(tmp_path, data, track=None, clip=None, tile=None):
    data = copy.deepcopy(data)
    lane = data["tracks"]["children"][0]
    lane["metadata"]["haptic_timeline"].update(track or {})
    lane["children"][1]["metadata"]["haptic_timeline"].update(clip or {})
    if tile is not None:
        tiles = data["metadata"]["haptic_timeline"]["tiles"]
        tiles[next(iter(tiles))] = tile
    path = tmp_path / "f.otio"
    path.write_text(json.dumps(data))
    return path


def test_words_and_number_text_read_as_what_they_say(tmp_path, exported):
    path = _write(
        tmp_path,
        exported,
        track={"mute": "false", "solo": "TRUE", "gain": "0.5"},
        clip={"reverse": "false", "gain": "0.25", "stretch": 2},
    )
    imported = _read(path)
    (info,) = imported.tracks
    assert (info.mute, info.solo, info.gain) == (False, True, 0.5)
    (placement,) = imported.placements
    assert placement.clip["reverse"] is False
    assert (placement.clip["gain"], placement.clip["stretch"]) == (0.25, 2.0)
    assert placement.start == 0.1


@pytest.mark.parametrize(
    ("track", "clip", "message"),
    [
        ({"gain": float("nan")}, {}, "the gain of track 'D' in f.otio must be a finite number"),
        ({"mute": "maybe"}, {}, "the mute of track 'D' in f.otio must be true or false"),
        ({}, {"gain": "1e400"}, "a clip's gain in f.otio must be a finite number, not '1e400'"),
        ({}, {"stretch": "x"}, "a clip's stretch in f.otio must be a number, not 'x'"),
        ({}, {"reverse": 2}, "a clip's reverse in f.otio must be true or false"),
        ({}, {"start": -1.0}, "starts at -1 s, before the timeline's start at 0"),
        ({}, {"stretch": 0}, "stretch must be positive"),
    ],
)
def test_a_field_with_no_meaning_is_one_sentence(tmp_path, exported, track, clip, message):
    with pytest.raises(FormatError, match=message.replace("(", r"\(")):
        _read(_write(tmp_path, exported, track=track, clip=clip))


def test_a_refused_import_leaves_the_project_as_it_was(tmp_path, exported):
    chirp = {
        "type": "generator",
        "generator": "chirp",
        "duration": 0.5,
        "params": {"f0": 0, "f1": 100, "amplitude": 1, "exponential": 1},
        "name": "sweep",
    }
    project = tmp_path / "p.htl"
    projectfile.save(edits.new_project(templates=False), project)
    before = project.read_bytes()
    with pytest.raises(FormatError, match="exponential chirp's f0 must be above 0"):
        importing.import_into_project_file(_write(tmp_path, exported, tile=chirp), project)
    assert project.read_bytes() == before


def test_a_tile_that_cannot_render_is_refused(tmp_path, exported):
    """Ten samples at 1e-300 Hz (accepted once, every render of the project failing after it)
    are refused, by the sampled tile's own rate check; an unrenderable one by the OTIO reader's."""
    samples = base64.b64encode(np.ones(10, dtype="<f8").tobytes()).decode("ascii")
    tiny = {"type": "sampled", "rate": 1e-300, "name": "slow", "samples": samples}
    with pytest.raises(FormatError, match=r"rate must be from 0.001 to 1e\+09 .*not 1e-300"):
        _read(_write(tmp_path, exported, tile=tiny))
