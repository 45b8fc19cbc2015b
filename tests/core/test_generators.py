"""Generator tiles rendered at a rate equal their closed forms."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from timeline.signal.band_limit import band_limited
from timeline.signal.generators import GENERATORS
from timeline.signal.render_presets import preset
from timeline.tiles import generator, spline

NORMAL = preset("normal")


@pytest.mark.parametrize("rate", [1.0, 100.0, 10_000.0, 44_100.0, 192_000.0])
def test_sine_equals_closed_form_at_any_rate(rate):
    tile = generator("sine", 2.0, frequency=0.25, phase=0.3, amplitude=0.7)
    n = int(2.0 * rate)
    t = np.arange(n) / rate
    got = tile.render(0.0, 1.0 / rate, n, NORMAL)
    np.testing.assert_allclose(got, 0.7 * np.sin(2 * np.pi * 0.25 * t + 0.3), atol=1e-14)


def test_linear_chirp_phase_is_the_integral_of_its_frequency():
    tile = generator("chirp", 1.0, f0=10.0, f1=30.0)
    t = np.arange(10_000) / 10_000
    expected = np.sin(2 * np.pi * (10 * t + 10 * t * t))
    np.testing.assert_allclose(tile.render(0.0, 1e-4, 10_000, NORMAL), expected, atol=1e-12)


def test_exponential_chirp_reaches_its_end_frequency():
    tile = generator("chirp", 1.0, f0=10.0, f1=40.0, exponential=1.0)
    # instantaneous frequency = d(phase)/dt / 2pi at t=1 is f1
    h = 1e-7
    u = np.array([1.0 - h, 1.0 - 2 * h])
    phase = np.arcsin(tile.evaluate(u))
    assert abs(abs(phase[0] - phase[1]) / h / (2 * np.pi) - 40.0) < 1e-2


def test_square_triangle_saw_values():
    sq = generator("square", 1.0, frequency=1.0, duty=0.25)
    assert list(sq.evaluate(np.array([0.1, 0.3, 0.9]))) == [1.0, -1.0, -1.0]
    tri = generator("triangle", 1.0, frequency=1.0)
    np.testing.assert_allclose(tri.evaluate(np.array([0.0, 0.25, 0.5, 0.75])), [-1, 0, 1, 0])
    saw = generator("saw", 1.0, frequency=2.0)
    np.testing.assert_allclose(saw.evaluate(np.array([0.0, 0.125, 0.25])), [-1.0, -0.5, 0.0])


def test_ramp_constant_and_outside_is_zero():
    ramp = generator("ramp", 2.0, start=1.0, end=3.0)
    np.testing.assert_allclose(ramp.evaluate(np.array([0.0, 1.0, 2.0, 2.5, -0.1])), [1, 2, 3, 0, 0])
    const = generator("constant", 1.0, value=-4.5)
    assert const.evaluate(np.array([0.5]))[0] == -4.5


def test_noise_is_seeded_and_identical_at_shared_points_for_any_rate():
    a = generator("noise", 1.0, seed=7, bandwidth=50.0)
    b = generator("noise", 1.0, seed=8, bandwidth=50.0)
    coarse = a.render(0.0, 1e-3, 1000, NORMAL)
    fine = a.render(0.0, 1e-4, 10_000, NORMAL)
    np.testing.assert_allclose(fine[::10], coarse, atol=1e-12)
    assert not np.allclose(coarse, b.render(0.0, 1e-3, 1000, NORMAL))
    assert np.abs(coarse).max() <= 1.0 and 0.2 < coarse.std() < 0.7


def test_detents_have_stable_rest_points_where_torque_falls_through_zero():
    tile = generator("detents", 4.0, count=4.0, phase=-0.5)
    u = np.linspace(0, 4.0, 40_001)
    v = tile.evaluate(u)
    falling = np.flatnonzero((v[:-1] > 0) & (v[1:] <= 0))
    np.testing.assert_allclose(u[falling], [0.5, 1.5, 2.5, 3.5], atol=1e-3)


def test_wall_adsr_stribeck_am_shapes():
    wall = generator("wall", 1.0, edge=0.5, width=0.25)
    np.testing.assert_allclose(wall.evaluate(np.array([0.4, 0.625, 0.9])), [0, -0.5, -1])
    adsr = generator("adsr", 1.0, attack=0.1, decay=0.1, sustain=0.5, release=0.2)
    np.testing.assert_allclose(
        adsr.evaluate(np.array([0.05, 0.1, 0.15, 0.5, 0.9, 1.0])), [0.5, 1.0, 0.75, 0.5, 0.25, 0.0]
    )
    stribeck = generator(
        "stribeck",
        2.0,
        static=1.0,
        coulomb=0.5,
        stribeck_velocity=0.1,
        viscous=0.0,
        velocity_range=1.0,
    )
    # just above zero velocity the static level, far above the Coulomb level
    assert abs(stribeck.evaluate(np.array([1.0 + 1e-9]))[0] - 1.0) < 1e-6
    assert abs(stribeck.evaluate(np.array([2.0]))[0] - 0.5) < 1e-12
    am = generator("am", 1.0, carrier=100.0, modulation=0.0, depth=0.0, amplitude=2.0)
    np.testing.assert_allclose(am.evaluate(np.array([0.0025])), [2.0])


def test_every_generator_renders_finite_values():
    for name in GENERATORS:
        tile = generator(name, 1.0)
        values = tile.render(0.0, 1e-3, 1001, NORMAL)
        assert np.isfinite(values).all(), name


@settings(max_examples=150, deadline=None)
@given(
    st.sampled_from(sorted(GENERATORS) + ["natural spline", "pchip spline"]),
    st.floats(-1.0, 3.0),
    st.floats(1e-5, 1e-2),
    st.booleans(),
    st.integers(1, 3_000),
)
def test_a_grid_rendered_with_its_ends_as_bounds_equals_the_shape_evaluated_there(
    name, u0, du, backwards, n
):
    """Renders take a grid's least and greatest u from its ends (skipping masks and clips that
    do nothing there): every sample has the bits of the same shape evaluated at the same u,
    inside, across and outside the tile, forwards and backwards (reversed clips)."""
    du = -du if backwards else du
    grid = u0 + du * np.arange(n)
    if name.endswith("spline"):
        tile = spline([(0.2, 0.5), (0.7, -1.0), (1.1, 0.3), (1.8, 0.9)], 2.0, name.split()[0])
        expected = tile.evaluate(grid)
    else:
        tile = generator(name, 2.0)
        params = dict(tile.params)
        expected = band_limited(name, grid, 0.5 / abs(du), 2.0, params, tile.evaluate)
    assert np.array_equal(tile.render(u0, du, n, NORMAL), expected)
