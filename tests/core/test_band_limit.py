"""Generators above the output's Nyquist frequency are removed, not aliased; the rest is exact."""

import numpy as np

from timeline import edits
from timeline.band_limit import aliasing_notes
from timeline.cli import main as cli
from timeline.mixer import render
from timeline.projectfile import save
from timeline.tiles import generator

RATE = 10_000.0


def _project(tile, stretch: float = 1.0):
    p, track = edits.add_track(edits.new_project(), "drive")
    p, tile_id = edits.add_tile(p, tile)
    p, clip = edits.add_clip(p, track, tile_id, 0.0)
    if stretch != 1.0:
        p = edits.stretch_clip(p, clip, stretch, "squeeze")
    return p


def _drive(p):
    return render(p, 0.0, p.duration, RATE, "exact")["drive"] / p.tracks[0].gain


def test_a_7khz_sine_at_10khz_is_removed_not_a_3khz_tone():
    out = _drive(_project(generator("sine", 0.1, frequency=7000.0, amplitude=1.0)))
    assert out.size == 1000 and np.abs(out).max() == 0.0  # was a full-level 3 kHz alias


def test_a_sine_below_nyquist_is_untouched():
    p = _project(generator("sine", 0.1, frequency=4000.0, amplitude=1.0))
    out = _drive(p)
    t = np.arange(out.size) / RATE
    scale = out[1] / np.sin(2 * np.pi * 4000.0 * t[1])
    assert np.allclose(out, scale * np.sin(2 * np.pi * 4000.0 * t), atol=1e-12 * abs(scale))


def test_a_chirp_is_cut_where_it_crosses_nyquist():
    p = _project(generator("chirp", 1.0, f0=1000.0, f1=9000.0, amplitude=1.0))
    out = _drive(p)
    t = np.arange(out.size) / RATE
    crossing = (5000.0 - 1000.0) / 8000.0  # 0.5 s: the instantaneous frequency reaches 5 kHz
    assert np.abs(out[t >= crossing]).max() == 0.0
    assert np.abs(out[t < crossing - 0.01]).max() > 0.17  # full level below (0.18 N*m)


def test_squeezing_a_sine_past_nyquist_removes_it():
    p = _project(generator("sine", 1.0, frequency=3000.0), stretch=0.5)  # plays at 6 kHz
    assert np.abs(_drive(p)).max() == 0.0
    assert "above the 5000 Hz Nyquist" in aliasing_notes(p, RATE)[0]


def test_square_waves_with_aliasing_harmonics_are_named(tmp_path, capsys):
    p = _project(generator("square", 0.1, frequency=2000.0))
    notes = aliasing_notes(p, RATE)
    assert (
        len(notes) == 1 and "harmonics of its 2000 Hz square wave above 5000 Hz alias" in notes[0]
    )
    assert aliasing_notes(_project(generator("square", 0.1, frequency=100.0)), RATE) == []
    path = tmp_path / "sq.htl"
    save(p, path)
    assert cli.main(["render", str(path), "-o", str(tmp_path / "o.csv")]) == 0
    assert "warning: clip" in capsys.readouterr().err


def test_play_names_aliasing_clips_before_playing(tmp_path, capsys):
    path = tmp_path / "sq.htl"
    save(_project(generator("square", 0.02, frequency=2000.0)), path)
    assert cli.main(["play", str(path)]) == 0
    err = capsys.readouterr().err
    assert "warning: clip" in err and "square wave above 5000 Hz alias" in err
