"""The whole-loop test finds root magnitudes in pieces a stale check can stop between."""

from __future__ import annotations

import numpy as np
import pytest

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
