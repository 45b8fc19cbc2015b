"""The whole-loop test finds root magnitudes in pieces a stale check can stop between."""

from __future__ import annotations

import numpy as np
import pytest

from timeline.limits import servo
from timeline.limits.servo import loop_radius


def test_pieces_give_the_roots_of_each_polynomial_and_can_be_stopped():
    rng = np.random.default_rng(7)
    roots = rng.uniform(-1.5, 1.5, (10, 3))  # real roots: the largest magnitude is known
    polys = np.array([np.poly(r) for r in roots])
    expected = np.abs(roots).max(axis=1)
    calls: list[int] = []
    found = loop_radius(polys, lambda: calls.append(1), rows=4)
    np.testing.assert_allclose(found, expected, rtol=1e-9)
    assert len(calls) == 3  # 4 + 4 + 2 rows

    def stale() -> None:
        raise TimeoutError("stale")

    with pytest.raises(TimeoutError):
        loop_radius(polys, stale, rows=4)


def test_the_whole_loop_judged_in_pieces_is_the_same_and_stops_between_them(monkeypatch):
    """The unstable samples' polynomials and their distinct rows are built a piece at a time (at
    20,000 clips one pass over all of them took 25 s without a point to stop at)."""
    from device.sim import KnobParams

    p = KnobParams(estimator="kalman")
    rng = np.random.default_rng(3)
    n = 400
    k = np.repeat(rng.uniform(0.0, 40.0, n // 4), 4)  # runs of equal samples, as held layers
    b = np.repeat(rng.uniform(-0.05, 0.2, n // 4), 4)
    m = np.zeros(n)
    whole = servo.whole_loop(p.dynamics, p.period, k, b, m)
    assert 0 < whole.any.sum() < n  # stable and unstable samples both
    calls: list[int] = []
    monkeypatch.setattr(servo, "PIECE", 7)
    pieces = servo.whole_loop(p.dynamics, p.period, k, b, m, interrupt=lambda: calls.append(1))
    np.testing.assert_array_equal(pieces.radius, whole.radius)  # bit for bit
    assert len(calls) >= whole.any.sum() // 7

    def stale() -> None:
        raise TimeoutError("stale")

    with pytest.raises(TimeoutError):
        servo.whole_loop(p.dynamics, p.period, k, b, m, interrupt=stale)
