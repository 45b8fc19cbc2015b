"""Files written by the code of each older schema open with today's code, every migration running.

tests/golden/schema1.htl and schema2.htl were saved by the code before each schema bump (see
tests/golden/README.md); each holds a drive, a stiffness and a damping track, a 10 Hz sine with
a linear fade-in and an s-curve fade-out, a 5 Hz sine stretched by 2, a sampled ramp, a pchip
spline with an exponential fade-out, and two variants (schema 2 adds a vibration tile).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from timeline import render
from timeline.files import projectfile
from timeline.model import Fade
from timeline.plugins.track_kinds import track_kind
from timeline.tiles import SampledTile
from timeline.tiles.vibration_tile import VibrationTile

GOLDEN = Path(__file__).resolve().parents[1] / "golden"


def _load_counting_migrations(path: Path, monkeypatch) -> tuple[object, list[int]]:
    ran: list[int] = []

    def counted(version, step):
        return lambda doc: (ran.append(version), step(doc))[1]

    steps = {v: counted(v, step) for v, step in projectfile.MIGRATIONS.items()}
    monkeypatch.setattr(projectfile, "MIGRATIONS", steps)
    return projectfile.load(path), ran


@pytest.mark.parametrize(("schema", "steps"), [(1, [1, 2, 3, 4]), (2, [2, 3, 4])])
def test_an_old_file_opens_through_every_migration(schema, steps, monkeypatch):
    path = GOLDEN / f"schema{schema}.htl"
    assert f'"schema": {schema},' in path.read_text()
    project, ran = _load_counting_migrations(path, monkeypatch)
    assert ran == steps
    assert project.markers == () and project.loop is None  # schema 3 added them: none yet
    drive, spring, damping = project.tracks
    assert [t.kind for t in project.tracks] == ["drive", "stiffness", "damping"]
    assert spring.gain == 0.5
    sine = drive.clips[0]
    assert (sine.start, sine.gain, sine.source_out) == (0.1, 0.5, 0.5)
    assert sine.fade_in == Fade(0.05, "linear") and sine.fade_out == Fade(0.1, "s-curve")
    slow = spring.clips[0]
    assert (slow.start, slow.gain, slow.stretch, slow.duration) == (0.0, 0.8, 2.0, 0.8)
    ramp, swell = damping.clips
    assert (ramp.start, ramp.gain, swell.start, swell.gain) == (0.05, 0.3, 0.5, 0.6)
    assert swell.fade_out == Fade(0.2, "exponential")
    recording = project.tile(ramp.tile_id)
    assert isinstance(recording, SampledTile) and recording.rate == 200.0
    assert np.array_equal(recording.data, np.linspace(-1.0, 1.0, 41))  # stored losslessly
    assert project.tile(swell.tile_id).points == ((0.0, 0.0), (0.1, 0.3), (0.4, 1.0))
    assert [v.name for v in project.variants] == ["A", "B: stronger"]
    assert project.variants[1].tracks[0].clips[0].gain == 0.9
    assert project.active_variant == "A"


@pytest.mark.parametrize("schema", [1, 2])
def test_an_old_file_renders_the_closed_forms(schema):
    project = projectfile.load(GOLDEN / f"schema{schema}.htl")
    layers = render(project)
    rate = project.rate
    drive = track_kind("drive").full_scale
    # the 10 Hz sine from 0.1 s at gain 0.5: a crest at 0.325 s, past the 0.05 s fade-in
    assert layers["drive"][round(0.325 * rate)] == pytest.approx(0.5 * drive, rel=1e-12)
    # halfway through the linear fade-in (0.125 s), a crest too: half of it
    assert layers["drive"][round(0.125 * rate)] == pytest.approx(0.25 * drive, rel=1e-12)
    # the 5 Hz sine stretched by 2 plays at 2.5 Hz: a crest at 0.1 s; track gain 0.5, clip 0.8
    expected = 0.5 * 0.8 * track_kind("stiffness").full_scale * math.sin(2 * math.pi * 2.5 * 0.1)
    assert layers["stiffness"][round(0.1 * rate)] == pytest.approx(expected, rel=1e-12)
    # the spline's knot (0.1 s, 0.3) at 0.6 s, gain 0.6, before its fade-out
    damping = 1e-4  # the damping full scale before schema 5, pinned on load
    assert layers["damping"][round(0.6 * rate)] == pytest.approx(0.6 * 0.3 * damping, rel=1e-12)


def test_a_schema_2_file_keeps_its_vibration_tile():
    project = projectfile.load(GOLDEN / "schema2.htl")
    clip = project.tracks[0].clips[1]
    tile = project.tile(clip.tile_id)
    assert isinstance(tile, VibrationTile) and (clip.start, clip.gain) == (0.7, 0.6)
    assert tile.sharpness == "linear" and tile.source == "buzz.ahap"
    assert tile.design.amplitude == ((0.0, 0.2), (0.05, 1.0), (0.3, 0.0))
    assert [(e.time, e.amplitude, e.frequency) for e in tile.design.emphasis] == [(0.1, 0.9, 0.4)]
    assert len(render(project)["drive"]) == round(1.0 * project.rate)  # ends with it at 1.0 s
