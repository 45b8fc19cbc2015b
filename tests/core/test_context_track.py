"""The audio context track: kept out of every haptic render and export, mixed alone to listen."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from timeline import edits
from timeline.edits.sound_track import add_sound
from timeline.errors import EditError
from timeline.files.exporting import export_project_file
from timeline.files.projectfile import load, save
from timeline.rendering import mixer
from timeline.rendering.source_sound import has_sound, render_sound
from timeline.tiles import generator

RATE = 8000.0


def project_with_sound() -> tuple:
    p = edits.new_project(templates=False)
    p, drive = edits.add_track(p, "drive")
    p, tile = edits.add_tile(p, generator("constant", 0.5, value=0.5))
    p, _ = edits.add_clip(p, drive, tile, 0.0)
    sound = 0.25 * np.sin(2 * np.pi * 440 * np.arange(8000) / RATE)
    p, clip = add_sound(p, sound, RATE, name="beep", source="beep.wav")
    audio = p.tracks[-1].id
    return p, drive, audio, sound


def test_haptic_render_leaves_the_sound_out() -> None:
    p, _, _, _ = project_with_sound()
    layers = mixer.render(p, 0.0, 1.0, 1000.0)
    assert set(layers) == {"drive"}
    assert layers["drive"][:500] == pytest.approx(0.5 * 0.18)  # half of drive full scale
    assert layers["drive"][500:] == pytest.approx(0.0)


def test_sound_renders_alone_with_its_gain_mute_and_solo() -> None:
    p, drive, audio, sound = project_with_sound()
    heard = render_sound(p, 0.0, 1.0, RATE)
    np.testing.assert_allclose(heard, sound, atol=1e-6)
    louder = edits.set_track(p, audio, gain=2.0)
    np.testing.assert_allclose(render_sound(louder, 0.0, 1.0, RATE), 2 * sound, atol=1e-6)
    assert render_sound(edits.set_track(p, audio, mute=True), 0.0, 1.0, RATE) is None
    solo_drive = edits.set_track(p, drive, solo=True)
    assert render_sound(solo_drive, 0.0, 1.0, RATE) is None and not has_sound(solo_drive)
    solo_sound = edits.set_track(p, audio, solo=True)
    assert mixer.render(solo_sound, 0.0, 1.0, 1000.0) == {}
    assert has_sound(solo_sound)


def test_export_and_save_keep_the_sound_apart(tmp_path: Path) -> None:
    p, _, _, sound = project_with_sound()
    out = tmp_path / "layers.csv"
    save(p, tmp_path / "design.htl")
    export_project_file(tmp_path / "design.htl", out)
    header = out.read_text().splitlines()[0]
    assert "drive" in header and "audio" not in header
    again = load(tmp_path / "design.htl")
    np.testing.assert_array_equal(render_sound(again, 0.0, 1.0, RATE), render_sound(p, 0, 1, RATE))


def test_sound_goes_only_on_a_context_track() -> None:
    p, drive, _, sound = project_with_sound()
    with pytest.raises(EditError, match="audio"):
        add_sound(p, sound, RATE, track_id=drive)
