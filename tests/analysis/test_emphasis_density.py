"""Emphasis density follows the sound: synthetic click trains and a burst with known onsets."""

from __future__ import annotations

import numpy as np
import pytest

from tests.analysis.conftest import RATE
from timeline.analysis import AnalysisSettings, analyse
from timeline.analysis.agreement import onset_f1


def click_train(
    per_second: float, length: float = 2.0, seed: int = 1
) -> tuple[np.ndarray, np.ndarray]:
    """Noise clicks (3 ms, 1 ms decay) at a steady rate over a noise floor 36 dB down."""
    rng = np.random.default_rng(seed)
    x = 0.01 * rng.normal(size=int(length * RATE))
    onsets = np.arange(0.1, length - 0.05, 1.0 / per_second)
    click = np.arange(int(0.003 * RATE))
    for start in onsets:
        i = int(start * RATE)
        x[i : i + len(click)] += 0.6 * rng.normal(size=len(click)) * np.exp(-click / (0.001 * RATE))
    return x, onsets


def explosion(seed: int = 1) -> tuple[np.ndarray, np.ndarray]:
    """One burst at 0.3 s: noise and a 50 Hz rumble decaying over 0.4 s, over a noise floor."""
    rng = np.random.default_rng(seed)
    t = np.arange(2 * RATE) / RATE
    x = 0.005 * rng.normal(size=len(t))
    d = t[t >= 0.3] - 0.3
    x[t >= 0.3] += (
        0.8 * np.exp(-d / 0.4) * (0.6 * rng.normal(size=len(d)) + np.sin(2 * np.pi * 50 * d))
    )
    return x, np.array([0.3])


@pytest.mark.parametrize("per_second", [1, 5, 20])
def test_default_finds_the_clicks_of_a_train(per_second: int) -> None:
    x, onsets = click_train(per_second)
    found = analyse(x, RATE).emphasis[:, 0]
    assert onset_f1(found, onsets, tolerance=0.03) >= 0.8


def test_an_explosion_is_one_emphasis_however_sensitive() -> None:
    x, onsets = explosion()
    for sensitivity in (25, 50, 75):
        found = analyse(x, RATE, AnalysisSettings(sensitivity=sensitivity)).emphasis[:, 0]
        assert onset_f1(found, onsets, tolerance=0.03) >= 0.8


def test_sensitivity_spans_sparse_to_dense() -> None:
    x, onsets = click_train(25, length=4.0)
    span = onsets[-1] - onsets[0] + 1 / 25  # seconds of dense material

    def per_second(sensitivity: float) -> float:
        found = analyse(x, RATE, AnalysisSettings(sensitivity=sensitivity)).emphasis
        return len(found) / span

    assert per_second(1) <= 1.0
    assert per_second(100) >= 20.0
    densities = [per_second(s) for s in (1, 10, 25, 50, 100)]
    assert densities == sorted(densities) and 2 <= densities[1] <= 15  # smooth, not a switch


@pytest.mark.parametrize("chunk", [7, 40, 300])
def test_onsets_taken_chunk_by_chunk_are_those_of_the_whole(
    chunk: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The onset statistics in chunks (bounded memory for hours of frames) give the same hits as
    over all frames at once, whatever the chunk (smaller than the filters' reach, or larger)."""
    from timeline.analysis import onsets

    x, _ = click_train(20)
    x[RATE // 2 :] += explosion()[0][: len(x) - RATE // 2]
    whole = analyse(x, RATE).emphasis
    assert len(whole) >= 20
    monkeypatch.setattr(onsets, "CHUNK", chunk)
    np.testing.assert_array_equal(analyse(x, RATE).emphasis, whole)
