"""The RMS envelope follower: attack, hold and release times, and state across blocks."""

from __future__ import annotations

import numpy as np
import pytest

from timeline.analysis.envelope import EnvelopeFollower


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
