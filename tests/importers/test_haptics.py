"""OTIO round trips and recordings from the corpus (.haptic and AHAP: test_vibration_formats.py)."""

from __future__ import annotations

import numpy as np
import pytest

from timeline import edits
from timeline.files import exporting, importing
from timeline.model import Fade
from timeline.plugins.file_formats import FormatError
from timeline.tiles import SampledTile, generator

from .hand_wav import STEREO, STEREO_VALUES, write_wav


def test_otio_round_trip_keeps_clips_exactly(tmp_path):
    project = edits.new_project()
    project, drive = edits.add_track(project, "drive", "Buzz")
    project, stiff = edits.add_track(project, "stiffness", gain=0.5, mute=True)
    project, sine = edits.add_tile(project, generator("sine", 0.3, frequency=20))
    project, rec = edits.add_tile(project, SampledTile(np.linspace(-1, 1, 777), 1234.5, "rec"))
    project, _ = edits.add_clip(project, drive, sine, 0.1, gain=0.7, fade_in=Fade(0.05, "s-curve"))
    project, _ = edits.add_clip(
        project, drive, rec, 0.2, reverse=True, source_in=0.1, source_out=0.5
    )  # overlaps the first: a second OTIO lane
    project, _ = edits.add_clip(project, stiff, sine, 1 / 3, stretch=2.5, stretch_mode="repeat")
    exporting.export_project(project, tmp_path / "p.otio")
    back, _ = importing.import_file(edits.new_project(), tmp_path / "p.otio")
    assert [(t.kind, t.name, t.gain, t.mute) for t in back.tracks] == [
        (t.kind, t.name, t.gain, t.mute) for t in project.tracks
    ]
    for before, after in zip(project.tracks, back.tracks, strict=True):
        assert len(before.clips) == len(after.clips)
        for c0, c1 in zip(before.clips, after.clips, strict=True):
            assert (c0.start, c0.duration) == (c1.start, c1.duration)
            fields = (
                "source_in",
                "source_out",
                "stretch",
                "stretch_mode",
                "gain",
                "reverse",
                "fade_in",
                "fade_out",
            )
            assert all(getattr(c0, f) == getattr(c1, f) for f in fields)
            assert project.tile(c0.tile_id) == back.tile(c1.tile_id)


def test_foreign_otio_is_refused(tmp_path):
    import opentimelineio as otio

    otio.adapters.write_to_file(otio.schema.Timeline(name="film"), str(tmp_path / "f.otio"))
    with pytest.raises(FormatError, match="not written by haptic-timeline"):
        importing.read_file(tmp_path / "f.otio")


def test_corpus_recordings_import(corpus):
    for wav in sorted((corpus / "audio-pairs").glob("*.wav")):
        tile = importing.read_file(wav).placements[0].tile
        assert tile.rate > 0 and len(tile.data) > 100 and np.abs(tile.data).max() <= 1.0


def test_a_wav_built_by_hand_imports_as_its_samples(tmp_path):
    tile = importing.read_file(write_wav(tmp_path / "hand.wav", STEREO)).placements[0].tile
    assert tile.rate == 44_100 and tile.data.tolist() == STEREO_VALUES
