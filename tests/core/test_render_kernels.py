"""The compiled render loops give the bits of their numpy forms, so either may sum any render."""

from __future__ import annotations

import sys

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from timeline.bench.scenes import LargeSpec, large_project
from timeline.rendering import mixer
from timeline.signal import harmonic_waves
from timeline.signal.harmonic_waves import _fourier_real, harmonics_below, synthesise
from timeline.signal.render_kernels import fourier_real, scaled_add

ANY_FLOAT = st.floats(allow_nan=False, allow_infinity=False, width=64)


@pytest.mark.parametrize(
    "x",
    [[-0.0], [0.0, -3.5, 2.0], [5e-324, -5e-324], [1.0, -np.inf, 2.0], [1.0, np.nan, -7.0],
     [np.nan, np.inf], [np.inf, np.nan], list(np.random.default_rng(1).standard_normal(999))],
)  # fmt: skip
def test_the_compiled_peak_is_numpys_largest_magnitude(x, monkeypatch):
    values = np.array(x)
    values.setflags(write=False)  # pieces are read-only
    compiled = mixer.peak_of(values)
    monkeypatch.delitem(sys.modules, "timeline.signal.render_kernels")
    assert np.array_equal(compiled, mixer.peak_of(values), equal_nan=True)
    assert np.array_equal(compiled, np.max(np.abs(values)), equal_nan=True)


@settings(max_examples=100, deadline=None)
@given(
    arrays(np.float64, st.integers(0, 300), elements=ANY_FLOAT),
    st.data(),
    st.one_of(ANY_FLOAT, st.sampled_from([1e-308, 5e-324, 1e308, -0.0, 0.37])),
)
def test_scaled_add_rounds_like_numpy_multiply_then_add(x, data, weight):
    out = data.draw(arrays(np.float64, x.shape, elements=ANY_FLOAT))
    expected = out.copy()
    with np.errstate(over="ignore", invalid="ignore"):
        mixer._numpy_add(expected, x, weight, np.empty(7))  # in pieces of 7
    scaled_add(out, x, weight)
    assert np.array_equal(out, expected, equal_nan=True)  # overflow: inf/nan in both alike


@settings(max_examples=60, deadline=None)
@given(
    arrays(np.float64, st.integers(1, 700), elements=st.floats(-1e6, 1e6)),
    arrays(np.complex128, st.integers(1, 40), elements=st.complex_numbers(max_magnitude=10.0)),
    st.booleans(),
)
def test_compiled_fourier_sum_equals_the_numpy_sum_bit_for_bit(x, coefficients, odd):
    expected, got = np.empty(x.size), np.empty(x.size)
    _fourier_real(x, coefficients.real.copy(), coefficients.imag.copy(), odd, expected)
    fourier_real(x, coefficients.real.copy(), coefficients.imag.copy(), odd, got)
    assert np.array_equal(got, expected)


def _series(name: str, x: np.ndarray, keep: int, duty: float) -> np.ndarray:
    """The unit wave's Fourier series to harmonic `keep`, term by term (harmonic_waves' doc)."""
    k = np.arange(1, keep + 1)
    phase = 2 * np.pi * k * x[:, None]
    if name == "square":
        delayed = 2 * np.pi * k * (x[:, None] - duty)
        return (2 * duty - 1) + np.sum(2 / (np.pi * k) * (np.sin(phase) - np.sin(delayed)), axis=1)
    if name == "saw":
        return -np.sum(2 / (np.pi * k) * np.sin(phase), axis=1)
    odd = k % 2 == 1
    return -np.sum(8 / (np.pi**2 * k[odd] ** 2) * np.cos(phase[:, odd]), axis=1)


@pytest.mark.parametrize(
    ("name", "duty"), [("square", 0.3), ("square", 0.5), ("saw", 0.5), ("triangle", 0.5)]
)
@pytest.mark.parametrize("compiled", [False, True])
def test_the_fourier_sum_is_the_wave_it_synthesises(name, duty, compiled, monkeypatch):
    """A 30 Hz wave at 10 kHz with its 166 harmonics, numpy or compiled, odd-only or all: the
    series summed term by term, to 1e-12 of the amplitude."""
    monkeypatch.setattr(harmonic_waves, "COMPILED_WORK", 0 if compiled else 10**12)
    if not compiled:  # as in a process that has not loaded numba
        monkeypatch.delitem(sys.modules, "timeline.signal.render_kernels", raising=False)
    params = {"frequency": 30.0, "phase": 0.3, "amplitude": 0.8, "duty": duty}
    u = np.arange(2_000) / 10_000.0
    keep = harmonics_below(30.0, 5_000.0)
    assert keep == 166
    expected = 0.8 * _series(name, 30.0 * u + 0.3 / (2 * np.pi), keep, duty)
    got = synthesise(name, u, params, 5_000.0)
    assert np.max(np.abs(got - expected)) < 1e-12


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
