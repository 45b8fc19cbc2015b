"""OTIO exports name the timeline after the project and point clips at media rendered beside it."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import opentimelineio as otio
import soundfile as sf

from timeline import edits
from timeline.edits.vibration import Emphasis, VibrationDesign, design_of, place_design
from timeline.files import exporting, importing, projectfile
from timeline.rendering import mixer
from timeline.tiles import generator

BUZZ = Path(__file__).resolve().parents[2] / "projects" / "notification_buzz.htl"


def _project():
    design = VibrationDesign(
        ((0.0, 0.0), (0.05, 0.8), (0.3, 0.0)),
        ((0.0, 0.2), (0.3, 0.9)),
        (Emphasis(0.05, 1.0, 0.5),),
        0.3,
    )
    p = edits.new_project(templates=False, title="Door knock")
    p = place_design(p, design, at=0.1)
    p, stiff = edits.add_track(p, "stiffness", "Spring")
    p, tile = edits.add_tile(p, generator("ramp", 0.5))
    p, _ = edits.add_clip(p, stiff, tile, 0.0, gain=0.3)
    return p, design


def test_named_after_the_file_with_media_beside_it(tmp_path):
    project, design = _project()
    out = tmp_path / "knock.otio"
    exporting.export_project(project, out)
    timeline = otio.adapters.read_from_file(str(out))
    assert timeline.name == "Door knock"
    assert not any(p.name.startswith(".knock") for p in tmp_path.iterdir())  # no temporaries
    drive_clip = next(iter(timeline.tracks[0].find_clips()))
    refs = drive_clip.media_references()
    assert isinstance(drive_clip.media_reference, otio.schema.ExternalReference)
    assert sorted(refs) == ["DEFAULT_MEDIA", "haptic"]
    wav = tmp_path / drive_clip.media_reference.target_url
    assert wav.name == "knock-Drive_1.wav"
    samples, rate = sf.read(wav)
    assert rate == project.rate
    # the drive track ends at 0.4 s; its emphasis is on the Emphasis track below it
    drive = mixer.render(project, 0.0, 0.4, project.rate, "normal", [project.tracks[0].id])["drive"]
    assert len(samples) == len(drive) and np.max(np.abs(samples - drive)) < 1e-6  # float32 WAV
    assert drive_clip.source_range.start_time.to_seconds() == 0.1
    haptic = tmp_path / refs["haptic"].target_url
    shifted = design.shifted(0.1)
    envelopes = dataclasses.replace(shifted, emphasis=())
    assert design_of(importing.import_file(edits.new_project(templates=False), haptic)[0]) == (
        envelopes
    )
    accent = next(iter(timeline.tracks[1].find_clips()))  # the Emphasis track's .haptic
    haptic = tmp_path / accent.media_references()["haptic"].target_url
    assert haptic.name == "knock-Emphasis.haptic"
    alone = design_of(importing.import_file(edits.new_project(templates=False), haptic)[0])
    assert alone.emphasis == shifted.emphasis
    spring = next(iter(timeline.tracks[2].find_clips()))
    assert spring.media_reference.target_url == "knock-Spring.wav"
    assert "haptic" not in spring.media_references()
    # and it reads back exactly
    back, _ = importing.import_file(edits.new_project(templates=False), out)
    assert design_of(back) == design.shifted(0.1)


def test_the_example_project_exports_under_its_own_name(tmp_path):
    project = projectfile.load(BUZZ)
    out = tmp_path / "notification_buzz.otio"
    exporting.export_project(project, out)
    timeline = otio.adapters.read_from_file(str(out))
    title = project.metadata.get("title")
    assert timeline.name == (title or "notification_buzz") and not timeline.name.startswith(".")
    for clip in timeline.find_clips():
        assert (tmp_path / clip.media_reference.target_url).is_file()
