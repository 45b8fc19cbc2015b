"""The whole analysis on synthetic sounds with known onsets, envelopes and frequencies."""

from __future__ import annotations

import numpy as np
import pytest

from tests.analysis.conftest import RATE, tone_bursts
from timeline.analysis import AnalysisSettings, analyse, analyse_blocks
from timeline.analysis.agreement import on_grid
from timeline.analysis.sound import level_of
from timeline.errors import AnalysisError


def value_at(points: np.ndarray, t: float) -> float:
    return float(np.interp(t, points[:, 0], points[:, 1]))


def test_bursts_give_emphasis_at_their_onsets() -> None:
    onsets = [0.1, 0.45, 0.8]
    a = analyse(tone_bursts(onsets, 150.0, 1.2), RATE, AnalysisSettings(sensitivity=100))
    found = a.emphasis[:, 0]
    assert len(found) == 3
    np.testing.assert_allclose(found, onsets, atol=0.005)
    # not normalised (Studio's default): the follower's level at each 0.8-peak burst's top
    assert np.all((a.emphasis[:, 1] > 0.7) & (a.emphasis[:, 1] <= 0.8))
    # silence before the first burst (the level left is the sound's removed DC offset)
    assert value_at(a.amplitude, 0.05) < 5e-3
    assert value_at(a.amplitude, 0.4) < 0.05  # released between bursts


def test_sensitivity_passes_the_strongest_flux() -> None:
    """Meta's peak picking (not adaptive): sensitivity is a share of the flux range."""
    x = tone_bursts([0.1, 0.45, 0.8], 150.0, 1.2)

    def meta(**kw: float | bool) -> AnalysisSettings:
        return AnalysisSettings(adaptive=False, peak_window=0.1, **kw)  # type: ignore[arg-type]

    every = analyse(x, RATE, meta(sensitivity=100)).emphasis[:, 0]
    half = analyse(x, RATE, meta(sensitivity=50)).emphasis[:, 0]
    assert len(every) == 3 and 1 <= len(half) < 3 and set(half) <= set(every)
    assert len(analyse(x, RATE, meta(sensitivity=0)).emphasis) == 0
    assert len(analyse(x, RATE, meta(emphasis=False)).emphasis) == 0


def test_release_falls_99_percent_in_its_time() -> None:
    x = np.zeros(RATE)
    x[: RATE // 4] = np.where(np.arange(RATE // 4) % 2, 1.0, -1.0)  # full-scale, then silence
    s = AnalysisSettings(emphasis=False, hold=0.0, resolution=100, tail_ratio=1.0)  # all points
    a = analyse(x, RATE, s)
    assert value_at(a.amplitude, 0.2) == pytest.approx(1.0, abs=0.01)
    assert value_at(a.amplitude, 0.25 + s.release) == pytest.approx(0.01, abs=0.004)


@pytest.mark.parametrize("hz", [80.0, 200.0, 450.0])
def test_frequency_follows_a_tone(hz: float) -> None:
    t = np.arange(RATE // 2) / RATE
    a = analyse(0.5 * np.sin(2 * np.pi * hz * t), RATE)
    expected = (hz - 30.0) / (600.0 - 30.0)
    middle = a.frequency[(a.frequency[:, 0] > 0.1) & (a.frequency[:, 0] < 0.4), 1]
    np.testing.assert_allclose(middle, expected, atol=0.03)


def test_envelopes_span_the_sound_from_zero() -> None:
    a = analyse(tone_bursts([0.02], 200.0, 0.3), RATE)
    for env in (a.amplitude, a.frequency):
        assert env[0, 0] == 0.0 and env[-1, 0] == pytest.approx(0.3, abs=1e-3)
        assert np.all(np.diff(env[:, 0]) > 0) and np.all((env[:, 1] >= 0) & (env[:, 1] <= 1))


@pytest.mark.parametrize("block", [1000, 4096, 48_000])
def test_blocks_give_the_same_design(block: int) -> None:
    x = tone_bursts([0.05, 0.9, 1.6], 120.0, 2.5)
    s = AnalysisSettings(resolution=100)  # every point the budget keeps
    whole = analyse(x, RATE, s)
    parts = analyse_blocks(
        (x[i : i + block] for i in range(0, len(x), block)), RATE, len(x), level_of(x, s), s
    )
    # Summation order differs by block, so where two triangle areas tie to rounding the runs may
    # keep different, equally good breakpoints: the curves agree well within the reduction's error.
    grid = np.arange(0, 2.5, 1e-3)
    for ours, theirs in ((parts.amplitude, whole.amplitude), (parts.frequency, whole.frequency)):
        np.testing.assert_allclose(on_grid(ours, grid), on_grid(theirs, grid), atol=5e-3)
    np.testing.assert_allclose(parts.emphasis, whole.emphasis, atol=1e-12)


def test_silence_is_a_flat_zero_design() -> None:
    a = analyse(np.zeros(RATE // 10), RATE)
    assert np.all(a.amplitude[:, 1] == 0) and len(a.emphasis) == 0
    assert np.all(np.isfinite(a.frequency))


def test_one_sample_is_a_short_design() -> None:
    a = analyse(np.array([0.7]), 44_100)
    assert a.duration == pytest.approx(1e-3, abs=1e-4)
    assert np.all(np.isfinite(a.amplitude)) and np.all(np.isfinite(a.frequency))


def test_clipped_audio_stays_within_full_scale() -> None:
    x = np.clip(5 * tone_bursts([0.01], 100.0, 0.3), -1, 1)
    a = analyse(x, RATE)
    assert a.amplitude[:, 1].max() <= 1.0 and a.emphasis[:, 1].max() <= 1.0


def test_telephone_rate_audio() -> None:
    a = analyse(
        tone_bursts([0.1, 0.5], 300.0, 0.8, rate=8000), 8000, AnalysisSettings(sensitivity=100)
    )
    np.testing.assert_allclose(a.emphasis[:, 0], [0.1, 0.5], atol=0.005)


def test_bad_samples_are_one_sentence() -> None:
    with pytest.raises(AnalysisError, match="not finite"):
        analyse(np.array([0.0, np.nan, 0.1]), RATE)
    with pytest.raises(AnalysisError, match="no samples"):
        analyse(np.zeros(0), RATE)
    with pytest.raises(AnalysisError, match="sample rate"):
        analyse(np.zeros(10), 0.0)


def test_float32_spectra_match_float64(monkeypatch) -> None:
    from timeline.analysis import spectrum

    x = tone_bursts([0.05, 0.3], 220.0, 0.6) + 0.01 * np.random.default_rng(2).normal(size=28_800)
    fast = analyse(x, RATE, AnalysisSettings(sensitivity=100))
    monkeypatch.setattr(spectrum, "FRAME_DTYPE", np.float64)
    exact = analyse(x, RATE, AnalysisSettings(sensitivity=100))
    grid = np.arange(0, 0.6, 1e-3)
    np.testing.assert_allclose(
        on_grid(fast.frequency, grid), on_grid(exact.frequency, grid), atol=1e-5
    )
    np.testing.assert_allclose(fast.emphasis, exact.emphasis, atol=1e-5)
