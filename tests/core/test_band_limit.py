"""Generators above the output's Nyquist frequency are removed, not aliased; the rest is exact."""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from timeline import edits
from timeline.cli import main as cli
from timeline.files.projectfile import save
from timeline.rendering.aliasing import aliasing_notes
from timeline.rendering.mixer import render
from timeline.signal.band_limit import HIGHEST_FREQUENCY, band_limited
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


def test_square_waves_losing_their_third_harmonic_are_named(tmp_path, capsys):
    p = _project(generator("square", 0.1, frequency=2000.0))
    notes = aliasing_notes(p, RATE)
    assert (
        len(notes) == 1
        and "harmonics of its 2000 Hz square wave at or above 5000 Hz were" in (notes[0])
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
    assert "warning: clip" in err and "square wave at or above 5000 Hz were removed" in err


def _amplitude_at(out: np.ndarray, frequency: float) -> float:
    """The amplitude of the `frequency` component of one second of samples at RATE."""
    spectrum = np.abs(np.fft.rfft(out)) / (out.size / 2)
    return float(spectrum[np.fft.rfftfreq(out.size, 1.0 / RATE) == frequency][0])


def test_a_3khz_square_at_10khz_keeps_its_fundamental_and_folds_nothing_back():
    p = _project(generator("square", 1.0, frequency=3000.0, amplitude=1.0))
    out = _drive(p)
    sine = _drive(_project(generator("sine", 1.0, frequency=3000.0, amplitude=1.0)))
    level = _amplitude_at(sine, 3000.0)  # the track's full scale
    # Sampled naively, its 3rd (9 kHz), 7th (21 kHz), 13th, ... harmonics all fold onto 1 kHz:
    # 0.46 of the amplitude there. Band-limited, only the fundamental is left.
    assert np.isclose(_amplitude_at(out, 3000.0) / level, 4 / np.pi, rtol=1e-12)
    naive = generator("square", 1.0, frequency=3000.0).evaluate(np.arange(10_000) / RATE)
    assert _amplitude_at(naive, 1000.0) > 0.45
    assert _amplitude_at(out, 1000.0) < 1e-12 * level
    others = np.abs(np.fft.rfft(out)) / (out.size / 2)
    others[np.fft.rfftfreq(out.size, 1.0 / RATE) == 3000.0] = 0.0
    assert others.max() < 1e-12 * level


def test_a_square_fundamental_is_4_over_pi_of_its_amplitude():
    from timeline.signal.render_presets import preset

    tile = generator("square", 1.0, frequency=3000.0, amplitude=0.5)
    out = tile.render(0.0, 1.0 / RATE, 10_000, preset("exact"))
    assert np.isclose(_amplitude_at(out, 3000.0), 0.5 * 4 / np.pi, rtol=1e-12)


def test_a_low_square_still_looks_like_a_square():
    from timeline.signal.render_presets import preset

    tile = generator("square", 0.1, frequency=100.0)  # 49 harmonics below 5 kHz: band-limited
    out = tile.render(0.0, 1.0 / RATE, 1000, preset("exact"))
    assert not np.array_equal(out, tile.evaluate(np.arange(1000) / RATE))
    assert np.allclose(out[25::100], 1.0, atol=0.02) and np.allclose(out[75::100], -1.0, atol=0.02)


def test_band_limited_saw_and_triangle_match_their_harmonics():
    from timeline.signal.render_presets import preset

    for name, third in (("saw", -2 / (3 * np.pi)), ("triangle", 8 / (9 * np.pi**2))):
        out = generator(name, 1.0, frequency=1500.0).render(0.0, 1 / RATE, 10_000, preset("exact"))
        spectrum = np.fft.rfft(out) / (out.size / 2)
        f = np.fft.rfftfreq(out.size, 1.0 / RATE)
        assert np.isclose(np.abs(spectrum[f == 4500.0][0]), abs(third), rtol=1e-9)
        spectrum[np.isin(f, [1500.0, 3000.0, 4500.0])] = 0.0  # the 3 harmonics below 5 kHz
        assert np.abs(spectrum).max() < 1e-12


def test_a_square_whose_alias_is_under_the_limit_is_sampled_exactly():
    from timeline.signal.band_limit import ALIAS_LIMIT
    from timeline.signal.harmonic_waves import aliased_fraction
    from timeline.signal.render_presets import preset

    tile = generator("square", 1.0, frequency=5.0)  # 999 harmonics below 5 kHz
    assert aliased_fraction("square", dict(tile.params), 5000.0) < ALIAS_LIMIT
    grid = np.arange(10_000) / RATE
    assert np.array_equal(tile.render(0.0, 1 / RATE, 10_000, preset("exact")), tile.evaluate(grid))


def test_a_decimating_preset_band_limits_at_its_coarser_grid():
    from timeline.signal.render_presets import QualityPreset

    coarse = QualityPreset("coarse", "linear", "linear", 4, "float64")  # 2.5 kHz evaluation
    sine = generator("sine", 0.1, frequency=3000.0)
    assert np.abs(sine.render(0.0, 1 / RATE, 1000, coarse)).max() == 0.0


def test_export_names_clips_changed_at_its_rate(tmp_path, capsys):
    path = tmp_path / "sq.htl"
    save(_project(generator("square", 0.02, frequency=2000.0)), path)
    out = tmp_path / "sq.csv"
    assert cli.main(["export", str(path), "-o", str(out), "--rate", "10000"]) == 0
    err = capsys.readouterr().err
    assert "warning: clip" in err and "square wave at or above 5000 Hz were removed" in err
    assert cli.main(["export", str(path), "-o", str(out), "--rate", "48000"]) == 0
    assert "warning" not in capsys.readouterr().err


@settings(max_examples=150, deadline=None)
@given(
    st.sampled_from(["sine", "chirp", "am", "detents"]),
    st.floats(-4000.0, 4000.0),
    st.floats(1.0, 9000.0),
    st.booleans(),
    st.floats(-0.5, 2.5),
    st.floats(1e-4, 3.0),
)
def test_the_band_limit_skips_its_mask_only_where_nothing_reaches_nyquist(
    name, f0, f1, exponential, u0, span
):
    """Testing the ends of u's range gives exactly the per-sample mask, every sample's bits."""
    params = {
        "sine": {"frequency": f0},
        "chirp": {
            "f0": abs(f0) if exponential else f0,
            "f1": f1,
            "exponential": float(exponential),
        },
        "am": {"carrier": f0, "modulation": f1 / 100.0},
        "detents": {"count": f1 / 10.0},
    }[name]
    if name == "chirp" and exponential and params["f0"] == 0.0:
        params["f0"] = 1.0
    tile = generator(name, 2.0, **params)
    u = np.linspace(u0, u0 + span, 997)
    p = dict(tile.params)
    top = np.broadcast_to(HIGHEST_FREQUENCY[name](u, tile.duration, p), u.shape)
    reference = np.where(top < 2_500.0, tile.evaluate(u), 0.0)
    assert np.array_equal(
        band_limited(name, u, 2_500.0, tile.duration, p, tile.evaluate), reference
    )
