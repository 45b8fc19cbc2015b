"""Generator parameters a shape cannot render are refused in one sentence naming the parameter
(API and CLI), and noise wider than Nyquist renders band-limited at the level of its part below
Nyquist (checked against the spectrum's integral and against an ideal low-pass of a fine render)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from scipy.integrate import quad

from timeline import edits
from timeline.cli import main as cli
from timeline.errors import EditError
from timeline.files.projectfile import save
from timeline.rendering.aliasing import aliasing_notes
from timeline.rendering.mixer import render
from timeline.tiles import generator

BAD = [
    ("detents", {"count": 0.0}, "count"),
    ("chirp", {"f0": 0.0, "exponential": 1.0}, "f0"),
    ("chirp", {"f1": -5.0, "exponential": 1.0}, "f1"),
    ("stribeck", {"stribeck_velocity": 0.0}, "stribeck_velocity"),
    ("noise", {"bandwidth": 1e300}, "bandwidth"),
    ("noise", {"bandwidth": 0.0}, "bandwidth"),
    ("sine", {"frequency": math.nan}, "frequency"),
    ("am", {"depth": math.inf}, "depth"),
    ("noise", {"seed": -math.inf}, "seed"),
]


def _one_sentence(text: str, name: str) -> None:
    assert "\n" not in text.strip() and "Traceback" not in text
    assert f"{name} must" in text or f"{name!r} must" in text, text


@pytest.mark.parametrize(("name", "params", "bad"), BAD)
def test_the_api_refuses_a_parameter_in_one_sentence_naming_it(name, params, bad):
    with pytest.raises(EditError) as caught:
        generator(name, 1.0, **params)
    _one_sentence(str(caught.value), bad)


@pytest.mark.parametrize(("name", "params", "bad"), BAD)
def test_render_of_a_file_holding_it_prints_one_sentence_naming_it(tmp_path, capsys, name,
                                                                    params, bad):  # fmt: skip
    p, track = edits.add_track(edits.new_project(templates=False), "drive")
    p, tile_id = edits.add_tile(p, generator(name, 1.0))
    p, _ = edits.add_clip(p, track, tile_id, 0.0)
    path = tmp_path / "bad.htl"
    save(p, path)
    doc = json.loads(path.read_text())
    doc["project"]["tiles"][tile_id]["params"].update(params)
    path.write_text(json.dumps(doc))  # NaN and Infinity written as json's own spellings
    assert cli.main(["render", str(path), "-o", str(tmp_path / "out.csv")]) != 0
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err
    assert bad in err or "NaN" in err or "Infinity" in err, err


def _noise_project(bandwidth: float, seconds: float = 2.0):
    p, track = edits.add_track(edits.new_project(templates=False), "drive")
    p, tile_id = edits.add_tile(p, generator("noise", seconds, seed=11.0, bandwidth=bandwidth))
    p, _ = edits.add_clip(p, track, tile_id, 0.0)
    return p


def _in_band_rms(bandwidth: float, nyquist: float) -> float:
    """RMS of value noise's part below nyquist from its spectrum, independently of the code:
    lattice values of variance 1/3 every 1/(2 bandwidth), joined by h(x) = 1 - 3x^2 + 2|x|^3;
    its power below nyquist is (1/3) * the integral of |H(xi)|^2 over |xi| < nyquist/(2 bw),
    H integrated numerically from h."""

    def h_hat(xi: float) -> float:
        return 2 * quad(lambda x: (1 - 3 * x * x + 2 * x**3) * math.cos(2 * math.pi * xi * x),
                        0, 1)[0]  # fmt: skip

    c = nyquist / (2 * bandwidth)
    return math.sqrt(2 * quad(lambda xi: h_hat(xi) ** 2, 0, c, limit=200)[0] / 3)


def _drive(p, rate: float) -> np.ndarray:
    """The drive layer in tile units (over the track's gain and the drive's full scale)."""
    unit, track = edits.add_track(edits.new_project(templates=False), "drive")
    unit, tile_id = edits.add_tile(unit, generator("constant", 1.0, value=1.0))
    unit, _ = edits.add_clip(unit, track, tile_id, 0.0)
    scale = render(unit, 0.0, 0.001, rate)["drive"][0]
    return render(p, 0.0, p.duration, rate, "exact")["drive"] / scale


@pytest.mark.parametrize("bandwidth", [20_000.0, 7_000.0, 1e6])
def test_noise_above_nyquist_renders_at_the_rms_of_its_part_below_nyquist(bandwidth):
    p = _noise_project(bandwidth)
    out = _drive(p, 10_000.0)
    rms = float(np.sqrt(np.mean(out**2)))
    assert rms == pytest.approx(_in_band_rms(bandwidth, 5_000.0), rel=0.04)
    assert abs(float(np.mean(out))) < 0.05 * rms  # no offset
    notes = aliasing_notes(p, 10_000.0)
    assert len(notes) == 1 and "band-limited to 5000 Hz" in notes[0]


def test_20khz_noise_at_10khz_matches_an_ideal_low_pass_of_the_same_noise_rendered_finely():
    p = _noise_project(20_000.0)
    fine = _drive(p, 320_000.0)  # the noise as designed (its bandwidth far below 160 kHz)
    spectrum = np.fft.rfft(fine)
    spectrum[np.fft.rfftfreq(fine.size, 1 / 320_000.0) >= 5_000.0] = 0.0  # ideal low-pass
    reference = float(np.sqrt(np.mean(np.fft.irfft(spectrum, fine.size) ** 2)))
    rms = float(np.sqrt(np.mean(_drive(p, 10_000.0) ** 2)))
    assert rms == pytest.approx(reference, rel=0.05)
    full = float(np.sqrt(np.mean(fine**2)))
    assert rms < 0.65 * full  # an aliased render keeps (nearly) all of it: ~1.75x this


def test_noise_below_nyquist_is_the_designed_value_noise_unchanged():
    p = _noise_project(50.0)
    t = np.arange(20_000) / 10_000.0
    tile = p.tiles[p.tracks[0].clips[0].tile_id]
    assert np.allclose(_drive(p, 10_000.0), tile.evaluate(t), rtol=0, atol=1e-12)
    assert aliasing_notes(p, 10_000.0) == []
