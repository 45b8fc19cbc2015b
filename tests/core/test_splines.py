"""Our spline curves equal scipy's (the reference) within rounding, at extremes too."""

from __future__ import annotations

import numpy as np
from hypothesis import assume, example, given, settings
from hypothesis import strategies as st
from scipy.interpolate import CubicSpline, PchipInterpolator

from timeline.signal.splines import SAMPLES_PER_PIECE, natural_cubic, pchip
from timeline.tiles import spline

TOLERANCE = 1e-11  # of the curve's magnitude: its value range, its largest value, at least 1


def _check(x: np.ndarray, y: np.ndarray) -> None:
    u = np.concatenate([np.linspace(x[0], x[-1], 2001), x])
    for ours, ref in (
        (natural_cubic(x, y), CubicSpline(x, y, bc_type="natural")),
        (pchip(x, y), PchipInterpolator(x, y)),
    ):
        # Close knots make a natural spline overshoot far beyond the points (1e4 for a 1e-5
        # gap); rounding then scales with the curve's own size, in scipy's solution as in ours.
        scale = max(1.0, float(np.ptp(y)), float(np.max(np.abs(ref(u)))))
        got = ours(u)
        assert np.isfinite(got).all()
        assert np.max(np.abs(got - ref(u))) <= TOLERANCE * scale
        np.testing.assert_allclose(ours(x), y, rtol=0, atol=TOLERANCE * scale)


@settings(max_examples=150, deadline=None)
@given(
    st.lists(
        st.tuples(st.floats(0, 100), st.floats(-1e6, 1e6)),
        min_size=3,
        max_size=40,
        unique_by=lambda p: p[0],
    )
)
@example([(0.0, 0.0), (1.0, 0.0), (0.99999, 1.0)])  # a 1e-5 gap: the curve reaches 1.9e4
def test_random_control_points_match_scipy(points):
    x, y = map(np.array, zip(*sorted(points), strict=True))
    if np.min(np.diff(x)) < 1e-6 * max(1.0, x[-1] - x[0]):
        return  # near-coincident knots: both are ill-conditioned, neither is the reference
    _check(x, y)


def test_extremes_flat_steps_huge_values_and_many_points():
    rng = np.random.default_rng(3)
    _check(np.array([0.0, 1.0, 2.0]), np.array([5.0, 5.0, 5.0]))
    _check(np.array([0.0, 1.0, 2.0, 3.0]), np.array([0.0, 0.0, 1.0, 1.0]))
    _check(np.array([0.0, 1e-3, 2.0, 7.5]), np.array([1e12, -1e12, 3.0, 1e12]))
    x = np.cumsum(rng.uniform(0.01, 1.0, 3000))
    _check(x, np.sin(x) + rng.normal(0, 0.1, x.size))


def test_pchip_keeps_monotone_data_monotone():
    x = np.array([0.0, 0.5, 0.6, 2.0, 2.1, 4.0])
    y = np.array([0.0, 0.1, 0.9, 1.0, 1.0, 3.0])
    u = np.linspace(0, 4, 4001)
    assert np.all(np.diff(pchip(x, y)(u)) >= -1e-15)


def test_a_spline_tile_evaluates_through_its_points_without_scipy_objects():
    tile = spline([(0.0, 0.0), (0.3, 1.0), (0.7, -0.5), (1.0, 0.0)], 1.2, "natural")
    values = tile.evaluate(np.array([0.0, 0.3, 0.7, 1.0, 1.1, 1.3, -0.1]))
    np.testing.assert_allclose(values, [0.0, 1.0, -0.5, 0.0, 0.0, 0.0, 0.0], atol=1e-15)
    assert type(tile._curve).__module__ == "timeline.signal.splines"


@settings(max_examples=60, deadline=None)
@given(
    st.lists(
        st.tuples(st.floats(0, 100), st.floats(-1e6, 1e6)),
        min_size=3,
        max_size=12,
        unique_by=lambda p: p[0],
    ),
    st.floats(-10, 110),
    st.floats(-120, 120),
    st.sampled_from(["natural", "pchip"]),
)
def test_a_grid_is_evaluated_piece_by_piece_with_the_same_bits(points, u0, span, method):
    """Ascending and descending grids (reversed clips) past both ends and across every knot."""
    x, y = np.array(sorted(points)).T
    assume(np.diff(x).min() > 1e-6)  # as in test_random_control_points_match_scipy
    curve = natural_cubic(x, y) if method == "natural" else pchip(x, y)
    u = u0 + span * np.arange(SAMPLES_PER_PIECE * len(x)) / (SAMPLES_PER_PIECE * len(x))
    i = np.clip(np.searchsorted(x, u, side="right") - 1, 0, len(x) - 2)  # a search per sample
    s = u - x[i]
    per_sample = ((curve.d[i] * s + curve.c[i]) * s + curve.b[i]) * s + curve.a[i]
    assert np.isfinite(per_sample).all() and np.array_equal(curve(u), per_sample)
