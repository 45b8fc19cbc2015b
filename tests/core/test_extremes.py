"""Extremes: tiny and huge amplitudes, one sample, an hour, 1 Hz to 192 kHz, 10,000 clips."""

import math

import numpy as np
import pytest

from timeline import Mixer, edits, render
from timeline.errors import EditError, RenderError
from timeline.tiles import SampledTile, generator

from .helpers import one_clip

FULL = 0.18


@pytest.mark.parametrize("amplitude", [1e-12, 1e12])
def test_tiny_and_huge_amplitudes_keep_their_relative_precision(amplitude):
    p, clip = one_clip(generator("sine", 1.0, frequency=10, amplitude=amplitude))
    p = edits.set_fade(p, clip, "in", 0.5, "exponential")
    out = render(p)["drive"]
    t = np.arange(10_000) / 10_000
    x = np.clip(t / 0.5, 0, 1)
    ref = FULL * amplitude * np.sin(2 * np.pi * 10 * t) * (1000.0**x - 1) / 999
    np.testing.assert_allclose(out, ref, rtol=1e-12, atol=amplitude * FULL * 1e-14)


def test_one_sample_clip_renders_exactly_one_sample():
    p, _ = one_clip(SampledTile([0.5], 10_000.0), start=0.25)
    out = render(p, 0.0, 0.5)["drive"]
    assert np.count_nonzero(out) == 1 and out[2500] == 0.5 * FULL


def test_one_hour_clip_renders_in_chunks_with_exact_values():
    p, _ = one_clip(generator("sine", 3600.0, frequency=0.01))
    mixer = Mixer(cache_bytes=64 * 2**20)
    total, checked = 0, 0
    for t0, layers in mixer.render_chunks(p, chunk=600.0):
        out = layers["drive"]
        total += len(out)
        idx = np.arange(0, len(out), 997_331)
        t = t0 + idx / 10_000
        np.testing.assert_allclose(out[idx], FULL * np.sin(2 * np.pi * 0.01 * t), atol=1e-12)
        checked += len(idx)
    assert total == 36_000_000 and checked > 30


@pytest.mark.parametrize("rate", [1.0, 7.0, 1000.0, 48_000.0, 192_000.0])
def test_rates_from_1hz_to_192khz(rate):
    p, _ = one_clip(generator("ramp", 4.0, start=0.0, end=4.0))
    out = render(p, 0.0, 4.0, rate)["drive"]
    assert len(out) == round(4 * rate)
    np.testing.assert_allclose(out, FULL * np.arange(len(out)) / rate, rtol=1e-12, atol=1e-15)


@pytest.mark.heavy
def test_sampled_tile_at_1hz_renders_at_192khz_band_limited():
    """A 0.05 Hz sine sampled at 1 Hz, played at 192 kHz, is the sine again between samples."""
    data = np.sin(2 * np.pi * 0.05 * np.arange(100))
    p, _ = one_clip(SampledTile(data, 1.0))
    out = render(p, 30.0, 32.0, 192_000.0)["drive"] / FULL
    t = 30.0 + np.arange(len(out)) / 192_000
    assert np.isfinite(out).all()
    np.testing.assert_allclose(out, np.sin(2 * np.pi * 0.05 * t), atol=1e-3)
    draft = render(p, 30.0, 32.0, 192_000.0, quality="draft")["drive"] / FULL
    assert draft[0] == pytest.approx(data[30], abs=1e-12)  # on a sample: the sample itself


def test_ten_thousand_overlapping_clips_match_an_fsum_reference():
    """Error bound stated: max abs error below 1e-12 relative to the sum of magnitudes."""
    rng = np.random.default_rng(5)
    p = edits.new_project(templates=False)
    p, track = edits.add_track(p, "drive")
    sines = []
    for f in range(1, 21):
        p, tile = edits.add_tile(p, generator("sine", 0.2, frequency=f * 5.0))
        sines.append((tile, f * 5.0))
    clips = []
    starts = rng.uniform(0, 0.1, 10_000).round(4)
    gains = rng.uniform(-1, 1, 10_000) * 10.0 ** rng.integers(-6, 6, 10_000)
    tracks = list(p.tracks)
    new_clips = []
    from dataclasses import replace

    from timeline.model import Clip

    for i, (s, g) in enumerate(zip(starts, gains, strict=True)):
        tile, f = sines[i % 20]
        new_clips.append(Clip(f"x{i}", tile, float(s), 0.0, 0.2, gain=float(g)))
        clips.append((float(s), float(g), f))
    p = replace(p, tracks=(replace(tracks[0], clips=tuple(new_clips)),))
    out = render(p, 0.0, 0.3)["drive"]
    for i in (0, 517, 1000, 1999, 2999):
        t = i / 10_000
        terms = [
            FULL * g * math.sin(2 * math.pi * f * (t - s)) for s, g, f in clips if s <= t < s + 0.2
        ]
        ref = math.fsum(terms)
        scale = math.fsum(abs(x) for x in terms) or 1.0
        assert abs(out[i] - ref) <= 1e-12 * scale


def test_overflowing_sum_is_a_clear_error_not_inf():
    p, clip = one_clip(generator("constant", 1.0, value=1e308), gain=1e2)
    with pytest.raises(RenderError, match="not a finite number at 0"):
        render(p)


def test_degenerate_edits_are_refused_clearly():
    p, clip = one_clip(generator("sine", 1.0))
    with pytest.raises(EditError, match="positive"):
        edits.stretch_clip(p, clip, 0.0)
    with pytest.raises(EditError, match="finite"):
        edits.set_clip_gain(p, clip, float("nan"))
    with pytest.raises(EditError, match="longer than the clip"):
        edits.set_fade(p, clip, "in", 2.0)
    with pytest.raises(EditError, match="not a finite"):
        SampledTile([0.0, float("inf")], 10.0)


@pytest.mark.parametrize("factor", [1e-3, 1e3])
def test_extreme_stretch_factors(factor):
    p, clip = one_clip(generator("sine", 1.0, frequency=10))
    p = edits.stretch_clip(p, clip, factor)
    out = render(p, 0.0, min(factor, 5.0))["drive"]
    assert np.isfinite(out).all()
    t = np.arange(len(out)) / 10_000
    np.testing.assert_allclose(
        out, FULL * np.sin(2 * np.pi * 10 / factor * t) * (t < factor), atol=1e-9
    )
