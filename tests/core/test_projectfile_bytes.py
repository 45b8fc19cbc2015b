"""The bytes of a saved project are pinned: a small project of every field against a golden file.

tests/golden/current.htl (schema 5) was written by `small_project()` saved with the code that
raised the damping and mass full scales: saving the same project must give the same bytes, its
JSON must be dumps' but for the recording (raw in the appendix there, base64 in dumps), and
loading it must give the same project. tests/golden/schema4.htl (the same project saved by the
code that brought the binary appendix) and schema3.htl (written by the code before the clip
schema became one table, samples as base64) must still load as that project, but for their
damping track of the kind's full scale, pinned to the old 1e-4 N*m*s/rad so it renders as it
did. A clip's absent fields take Clip's defaults.
"""

from __future__ import annotations

import dataclasses
import json
import math
from pathlib import Path

import numpy as np
import pytest

from timeline import edits
from timeline.edits import markers
from timeline.errors import FieldError
from timeline.files import media, projectfile
from timeline.model import Clip, Project, Track
from timeline.plugins.track_kinds import track_kind
from timeline.signal.vibration_design import Emphasis, VibrationDesign
from timeline.tiles import SampledTile, generator, spline
from timeline.tiles.vibration_tile import VibrationTile

GOLDEN = Path(__file__).resolve().parents[1] / "golden" / "current.htl"
SCHEMA3 = GOLDEN.with_name("schema3.htl")
SCHEMA4 = GOLDEN.with_name("schema4.htl")


def small_project() -> Project:
    """Tracks of four kinds; clips with fades, stretch, gain, scale, pivot, reverse; every tile
    type; a variant, markers and a loop region."""
    p = edits.new_project("time", templates=False, title="Pinned bytes", description="fields")
    p, drive = edits.add_track(p, "drive", "Buzz")
    p, spring = edits.add_track(p, "stiffness", "Spring")
    p, damping = edits.add_track(p, "damping", "Damping")
    p, torque = edits.add_track(p, "mass", "Mass")
    p = edits.set_track(p, spring, gain=0.5, mute=True)
    p = edits.set_track(p, torque, solo=True, full_scale=0.25)
    p, sine = edits.add_tile(p, generator("sine", 0.2, "tap", frequency=175.0))
    p, swell = edits.add_tile(p, spline([(0.0, 0.0), (0.1, 0.3), (0.4, 1.0)], 0.4, "pchip"))
    ramp = np.linspace(-1.0, 1.0, 41)
    p, rec = edits.add_tile(p, SampledTile(ramp, 200.0, "ramp", "ramp.wav"))
    amplitude, frequency = ((0.0, 0.2), (0.05, 1.0), (0.3, 0.0)), ((0.0, 0.5), (0.3, 0.8))
    design = VibrationDesign(amplitude, frequency, (Emphasis(0.1, 0.9, 0.4),), 0.3)
    p, buzz = edits.add_tile(p, VibrationTile(design, "buzz", "buzz.ahap", "linear"))
    p, a = edits.add_clip(p, drive, sine, 0.0, gain=0.8)
    p = edits.set_fade(p, a, "in", 0.02, "equal-power")
    p = edits.set_fade(p, a, "out", 0.05, "s-curve")
    p, b = edits.add_clip(p, drive, buzz, 0.5, gain=0.6)
    p, c = edits.add_clip(p, spring, swell, 0.1)
    p = edits.stretch_clip(p, c, 1.5, "squeeze")
    p = edits.scale_clip(p, c, 1.25, 0.1)
    p, d = edits.add_clip(p, damping, rec, 0.05, gain=0.3)
    p = edits.stretch_clip(p, d, 2.0, "repeat")
    p = edits.reverse_clip(p, d)
    p = edits.trim_clip(p, d, 0.1, 0.4)
    p, e = edits.add_clip(p, torque, sine, 0.3)
    p = edits.invert_clip(p, e, 0.05)
    p = edits.set_fade(p, e, "out", 0.1, "exponential")
    p = edits.save_variant(p, "A")
    p = edits.set_clip_gain(p, b, 0.9)
    p = edits.save_variant(p, "B: stronger buzz")
    p = edits.switch_variant(p, "A")
    p, _ = markers.add_marker(p, 0.25, "hit")
    p, _ = markers.add_marker(p, math.pi / 10)
    return markers.set_loop(p, 0.1, 0.7)


def test_saving_writes_the_pinned_bytes(tmp_path):
    path = tmp_path / "small.htl"
    projectfile.save(small_project(), path)
    assert path.read_bytes() == GOLDEN.read_bytes()


def test_the_pinned_json_is_dumps_but_for_the_recording_kept_raw():
    text, appendix = GOLDEN.read_bytes().split(b"\n" + media.SEPARATOR)
    saved, dumped = json.loads(text), json.loads(projectfile.dumps(small_project()))
    assert saved.pop("appendix") == {"bytes": 41 * 8}
    (key, raw), (key_b64, b64) = saved.pop("media").popitem(), dumped.pop("media").popitem()
    assert saved == dumped and key == key_b64 == f"sampled:{raw['blake2b']}"
    ramp = np.linspace(-1.0, 1.0, 41)
    assert appendix == ramp.astype("<f8").tobytes()
    assert media.decode(b64, "ramp").tobytes() == appendix


def test_the_pinned_file_loads_as_the_project():
    assert projectfile.load(GOLDEN) == small_project()


def _damping_pinned(tracks: tuple[Track, ...]) -> tuple[Track, ...]:
    return tuple(
        dataclasses.replace(t, full_scale=1e-4) if t.kind == "damping" else t for t in tracks
    )


@pytest.mark.parametrize("golden", [SCHEMA3, SCHEMA4])
def test_an_older_file_loads_with_its_damping_full_scale_pinned(golden):
    project, loaded = small_project(), projectfile.load(golden)
    damping = next(t for t in loaded.tracks if t.kind == "damping")
    assert damping.full_scale == 1e-4 and track_kind("damping").full_scale == 0.2
    assert next(t for t in loaded.tracks if t.kind == "mass").full_scale == 0.25  # set: kept
    assert loaded == dataclasses.replace(
        project,
        tracks=_damping_pinned(project.tracks),
        variants=tuple(
            dataclasses.replace(v, tracks=_damping_pinned(v.tracks)) for v in project.variants
        ),
    )


def test_the_schema_3_file_keeps_its_samples_as_base64():
    doc = json.loads(SCHEMA3.read_bytes())
    assert doc["schema"] == 3 and "appendix" not in doc
    assert [m["encoding"] for m in doc["media"].values()] == ["zlib+base64"]


def test_a_clip_of_only_the_required_fields_takes_clips_defaults():
    required = {"id": "c1", "tile": "tile1", "start": 0.5, "source_in": 0.0, "source_out": 0.2}
    assert [f.key for f in projectfile.CLIP_FIELDS if f.default is dataclasses.MISSING] == list(
        required
    )
    assert projectfile.clip_from_json(required, "clip") == Clip("c1", "tile1", 0.5, 0.0, 0.2)
    without_start = {k: v for k, v in required.items() if k != "start"}
    with pytest.raises(FieldError, match="clip has no 'start'"):
        projectfile.clip_from_json(without_start, "clip")
    with pytest.raises(FieldError, match=r"clip.fade_in has no 'shape'"):
        projectfile.clip_from_json({**required, "fade_in": {"length": 0.1}}, "clip")
