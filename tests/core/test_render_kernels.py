"""The compiled render loops give the bits of their numpy forms, so either may sum any render."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from timeline import mixer
from timeline.bench.scenes import LargeSpec, large_project
from timeline.harmonic_waves import _coefficients, _fourier_real, harmonics_below, synthesise
from timeline.render_kernels import fourier_real, scaled_add

ANY_FLOAT = st.floats(allow_nan=False, allow_infinity=False, width=64)


@settings(max_examples=200, deadline=None)
@given(
    arrays(np.float64, st.integers(0, 300), elements=ANY_FLOAT),
    st.data(),
    st.one_of(ANY_FLOAT, st.sampled_from([1e-308, 5e-324, 1e308, -0.0, 0.37])),
)
def test_scaled_add_rounds_like_numpy_multiply_then_add(x, data, weight):
    out = data.draw(arrays(np.float64, x.shape, elements=ANY_FLOAT))
    expected = out.copy()
    with np.errstate(over="ignore", invalid="ignore"):
        mixer._numpy_add(expected, x, weight, np.empty(x.size))
    scaled_add(out, x, weight)
    assert np.array_equal(out, expected, equal_nan=True)  # overflow: inf/nan in both alike


@settings(max_examples=60, deadline=None)
@given(
    arrays(np.float64, st.integers(1, 700), elements=st.floats(-1e6, 1e6)),
    arrays(np.complex128, st.integers(1, 40), elements=st.complex_numbers(max_magnitude=10.0)),
)
def test_compiled_fourier_sum_equals_the_numpy_sum_bit_for_bit(x, coefficients):
    expected, got = np.empty(x.size), np.empty(x.size)
    _fourier_real(x, coefficients.real.copy(), coefficients.imag.copy(), expected)
    fourier_real(x, coefficients.real.copy(), coefficients.imag.copy(), got)
    assert np.array_equal(got, expected)


def test_the_fourier_sum_is_the_wave_it_synthesises():
    """A 30 Hz square at 10 kHz with its 166 harmonics: mean + sum equals the series by hand."""
    params = {"frequency": 30.0, "phase": 0.3, "amplitude": 0.8, "duty": 0.3}
    u = np.arange(2_000) / 10_000.0
    keep = harmonics_below(30.0, 5_000.0)
    x = 30.0 * u + 0.3 / (2 * np.pi)
    k = np.arange(1, keep + 1)
    series = (2 * 0.3 - 1) + np.sum(
        2
        / (np.pi * k)
        * (np.sin(2 * np.pi * k * x[:, None]) - np.sin(2 * np.pi * k * (x[:, None] - 0.3))),
        axis=1,
    )
    assert keep == 166 and _coefficients("square", params, keep).size == 166
    assert np.max(np.abs(synthesise("square", u, params, 5_000.0) - 0.8 * series)) < 1e-12


def test_a_large_distinct_render_is_the_same_summed_by_numpy_or_compiled(monkeypatch):
    """Every clip its own shape, off-grid, squares synthesised: both adders, the same bits (the
    compiled loops are loaded by this module, so renders use them unless told otherwise)."""
    project = large_project(LargeSpec(8, 160, 20.0, 0, off_grid=True))
    compiled = mixer.Mixer().render(project, 0.0, 20.0)
    monkeypatch.setattr(mixer, "_adder", lambda starts, ends: mixer._numpy_add)
    summed_by_numpy = mixer.Mixer().render(project, 0.0, 20.0)
    assert compiled.keys() == summed_by_numpy.keys() == {"drive", "stiffness", "damping"}
    for kind, values in compiled.items():
        assert np.abs(values).max() > 0.0
        assert np.array_equal(values, summed_by_numpy[kind])
