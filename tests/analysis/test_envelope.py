"""The RMS envelope follower: attack, hold and release times, state across blocks, the tail."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from timeline.analysis import DEFAULTS
from timeline.analysis.envelope import EnvelopeFollower, expand_tail
from timeline.analysis.sound import analyse


def test_stages_reach_99_percent_in_their_time() -> None:
    # 1 s stages at 4 Hz: each stage covers 99 % of its step in 4 samples.
    f = EnvelopeFollower.create(4.0, 0.25, attack=1.0, hold=1.0, release=1.0)
    out = f.process(np.array([1.0] * 4 + [0.5] * 8))
    np.testing.assert_allclose(out[:4], [0.6837722, 0.9, 0.9683772, 0.99], rtol=1e-6)
    np.testing.assert_allclose(out[4:8], 0.99)  # held for a second
    np.testing.assert_allclose(out[8:], [0.6549516, 0.549, 0.5154951, 0.5049], rtol=1e-6)


def test_moving_rms_of_a_window() -> None:
    f = EnvelopeFollower.create(1.0, 2.0, attack=0.0, hold=0.0, release=0.0)
    out = f.process(np.array([1.0, 1.0, 0.0, 0.0]))
    np.testing.assert_allclose(out, [np.sqrt(0.5), 1.0, np.sqrt(0.5), 0.0])


@pytest.mark.parametrize("block", [1, 7, 1000])
def test_blocks_give_the_same_envelope(block: int) -> None:
    x = np.random.default_rng(3).normal(size=5000)
    whole = EnvelopeFollower.create(48_000, 1e-4, 1e-4, 1.5e-3, 0.1).process(x)
    f = EnvelopeFollower.create(48_000, 1e-4, 1e-4, 1.5e-3, 0.1)
    parts = np.concatenate([f.process(x[i : i + block]) for i in range(0, len(x), block)])
    np.testing.assert_allclose(parts, whole, rtol=1e-12, atol=1e-12)


def test_tail_below_the_threshold_falls_twice_as_fast_in_db() -> None:
    values = np.array([0.5, 0.1, 0.05, 0.01, 0.0])
    out = expand_tail(values, threshold=0.1, ratio=2.0)
    np.testing.assert_allclose(out, [0.5, 0.1, 0.025, 0.001, 0.0])
    assert expand_tail(values, 0.1, 1.0) is values and expand_tail(values, 0.0, 2.0) is values


def test_a_decay_keeps_its_level_down_to_20_db_under_the_peak_then_falls_twice_as_fast() -> None:
    """A 200 Hz tone decaying 60 dB/s (known envelope 0.5 * 10^(-3t)) through the analysis."""
    rate = 8000
    t = np.arange(rate) / rate
    tone = 0.5 * 10 ** (-3 * t) * np.sin(2 * np.pi * 200 * t)
    keep = dataclasses.replace(DEFAULTS, emphasis=False, tolerance=2e-4)
    plain = analyse(tone, rate, dataclasses.replace(keep, tail_ratio=1.0)).amplitude
    tail = analyse(tone, rate, keep).amplitude
    at = np.array([0.2, 0.3, 0.5, 0.6])  # -12, -18, -30, -36 dB under the sound's peak
    db_plain = 20 * np.log10(np.interp(at, *plain.T) / 0.5)
    db_tail = 20 * np.log10(np.interp(at, *tail.T) / 0.5)
    np.testing.assert_allclose(db_plain, -60 * at, atol=0.6)  # the follower tracks the decay
    np.testing.assert_allclose(db_tail[:2], db_plain[:2], atol=1e-6)
    np.testing.assert_allclose(db_tail[2:], -20 + 2 * (db_plain[2:] + 20), atol=0.5)
