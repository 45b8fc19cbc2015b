"""The compiled per-kind loops give the bits of the numpy forms they replace, shape by shape and
for a whole render of distinct clips."""

from __future__ import annotations

from unittest import mock

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import timeline.signal.shape_kernels  # noqa: F401  (loaded: the loops are taken)
from timeline.bench.scenes import LargeSpec, large_project
from timeline.model import Clip, Fade
from timeline.rendering.clip_render import render_shape
from timeline.rendering.mixer import Mixer
from timeline.signal import compiled, grid_shapes
from timeline.signal.render_presets import PRESETS
from timeline.signal.resample import _compiled_delay_matches, _fractional_delay
from timeline.tiles import generator, spline

QUALITY = PRESETS["normal"]
AMPLITUDES = st.one_of(
    st.sampled_from([1.0, -3.7, 1e-300, 5e-324, 1e300, -1e308]),
    st.floats(-1e6, 1e6, allow_nan=False),
)
LENGTHS = st.one_of(st.integers(1, 300), st.integers(1, 100_000))
SPACINGS = st.sampled_from([1e-4, -1e-4, 1 / 44_100, -1 / 7_919.3, 1 / 192_000, 1e-3, 0.037])


def _numpy_form(render):
    """render() with every compiled loop refused: the numpy forms alone."""
    with mock.patch.object(compiled, "compiled_wanted", lambda n: False):
        return render()


def _same_bits(tile, u0: float, du: float, n: int) -> None:
    compiled = tile.render(u0, du, n, QUALITY)
    expected = _numpy_form(lambda: tile.render(u0, du, n, QUALITY))
    assert compiled.dtype == expected.dtype == np.float64
    assert np.array_equal(compiled, expected, equal_nan=True)  # a 1e300 curve overflows alike


def _tile(kind: str, data: st.DataObject, duration: float, amplitude: float):
    f = st.floats(-2_000.0, 2_000.0, allow_nan=False)
    if kind == "am":
        return generator("am", duration, carrier=data.draw(f), modulation=data.draw(f),
                         depth=data.draw(st.floats(-3, 3)), amplitude=amplitude)  # fmt: skip
    seed = data.draw(st.integers(-(2**63), 2**64))
    bandwidth = data.draw(st.floats(0.01, 50_000.0))  # below and above the grid's Nyquist
    return generator("noise", duration, seed=seed, bandwidth=bandwidth, amplitude=amplitude)


@pytest.mark.parametrize("kind", ["am", "noise"])
@settings(max_examples=40, deadline=None)
@given(data=st.data(), amplitude=AMPLITUDES, duration=st.floats(1e-3, 20.0), n=LENGTHS,
       du=SPACINGS, start=st.floats(-0.5, 1.5))  # fmt: skip
def test_each_generator_loop_gives_the_numpy_bits(kind, data, amplitude, duration, n, du, start):
    tile = _tile(kind, data, duration, amplitude)
    _same_bits(tile, start * duration, du, n)  # grids inside, across and outside the tile


SINES = [
    generator("sine", 0.7, frequency=37.0, phase=-2.1, amplitude=-3.7),
    generator("sine", 2.0, frequency=-1_300.0, amplitude=5e-324),
    generator("sine", 1.0, frequency=0.0, phase=0.0, amplitude=1e308),
    generator("chirp", 1.3, f0=20.0, f1=300.0, amplitude=1e300),
    generator("chirp", 1.0, f0=400.0, f1=-90.0),
    generator("chirp", 0.9, f0=5.0, f1=1_200.0, exponential=1.0, amplitude=-1e-300),
    generator("chirp", 0.9, f0=1_200.0, f1=5.0, exponential=1.0),
    generator("detents", 1.5, count=12.0, phase=0.3),
    generator("detents", 1.0, count=-3.0, amplitude=1e308),
    generator("adsr", 1.0),
    generator("adsr", 0.8, attack=0.0, decay=0.3, sustain=-0.4, release=0.9),
    generator("adsr", 0.5, attack=0.2, decay=0.0, sustain=1e-310, release=0.0),
    generator("adsr", 2.0, attack=1.5, decay=1.0, sustain=0.7, release=1.2),  # phases overlap
]


@pytest.mark.parametrize("tile", SINES, ids=lambda t: t.generator)
@pytest.mark.parametrize(("u0", "du", "n"), [(0.0, 1e-4, 20_000), (-0.0, -1e-4, 3),
                                             (-0.3, 1 / 44_100, 60_000), (1.4, -1 / 7_919.3, 9_000),
                                             (0.123456789, 0.037, 40)])  # fmt: skip
def test_the_sine_chirp_detent_and_adsr_loops_give_the_numpy_bits(tile, u0, du, n):
    _same_bits(tile, u0 * tile.duration, du, n)  # -0.0: numpy's signed zeros kept


def test_an_exponential_chirp_of_one_frequency_keeps_numpy():
    params = dict(generator("chirp", 1.0, f0=50.0, f1=50.0, exponential=1.0).params)
    assert grid_shapes.generator_on_grid("chirp", params, 1.0, -0.0, -1e-4, 10, 5000.0) is None


@settings(max_examples=60, deadline=None)
@given(
    knots=st.lists(st.floats(0.0, 10.0), min_size=3, max_size=12, unique=True),
    data=st.data(),
    amplitude=AMPLITUDES,
    method=st.sampled_from(["natural", "pchip"]),
    n=LENGTHS,
    du=SPACINGS,
    start=st.floats(-1.0, 11.0),
)
def test_the_spline_loop_gives_the_numpy_bits(knots, data, amplitude, method, n, du, start):
    values = data.draw(st.lists(st.floats(-1, 1), min_size=len(knots), max_size=len(knots)))
    duration = max(knots) + data.draw(st.floats(0.0, 1.0))
    with np.errstate(all="ignore"):  # 1e300-high curves overflow alike in both forms
        tile = spline(list(zip(knots, (v * amplitude for v in values), strict=True)), duration,
                      method)  # fmt: skip
        _same_bits(tile, start, du, n)


@pytest.mark.skipif(
    not _compiled_delay_matches(), reason="this BLAS sums np.convolve otherwise: numpy is kept"
)
@settings(max_examples=60, deadline=None)
@given(n=LENGTHS, scale=st.sampled_from([1.0, 1e-300, 1e300, 5e-324]), seed=st.integers(0, 99),
       fraction=st.floats(0.0, 1.0, exclude_max=True))  # fmt: skip
def test_the_delay_loop_gives_the_np_convolve_bits(n, scale, seed, fraction):
    rng = np.random.default_rng(seed)
    x = rng.standard_normal(n + 200) * scale
    compiled_delay = _fractional_delay(x, 70, fraction, n)
    expected = _numpy_form(lambda: _fractional_delay(x, 70, fraction, n))
    assert np.array_equal(compiled_delay, expected)


SHAPES = st.sampled_from(["linear", "equal-power", "exponential", "s-curve"])


@settings(max_examples=80, deadline=None)
@given(
    length=st.floats(1e-3, 5.0),
    fade_in=st.tuples(st.floats(0.0, 1.0), SHAPES),
    fade_out=st.tuples(st.floats(0.0, 1.0), SHAPES),
    rate=st.sampled_from([10_000.0, 44_100.0, 7_919.3, 100.0]),
    n=LENGTHS,
    start=st.floats(-0.2, 1.0),
)
def test_the_fade_loop_gives_the_numpy_bits(length, fade_in, fade_out, rate, n, start):
    clip = Clip("c", "t", 0.0, 0.0, length, fade_in=Fade(fade_in[0] * length, fade_in[1]),
                fade_out=Fade(fade_out[0] * length, fade_out[1]))  # fmt: skip
    tile = generator("sine", 5.0, frequency=37.0)
    compiled = render_shape(clip, tile, start * length, rate, n, QUALITY)
    expected = _numpy_form(lambda: render_shape(clip, tile, start * length, rate, n, QUALITY))
    assert np.array_equal(compiled, expected)


def test_the_loops_are_taken_once_loaded_and_left_where_numpy_masks():
    args = (1.0, 0.0, 1e-4, 10_000, 5000.0)
    for name in ("sine", "chirp", "detents", "am", "noise", "adsr"):
        tile = generator(name, 1.0)
        assert grid_shapes.generator_on_grid(name, dict(tile.params), *args) is not None, name
    high = dict(generator("am", 1.0, carrier=4_990.0, modulation=20.0).params)  # past Nyquist
    assert grid_shapes.generator_on_grid("am", high, *args) is None
    for name in ("square", "wall"):
        assert grid_shapes.generator_on_grid(name, dict(generator(name, 1.0).params), *args) is None


def test_a_render_of_distinct_clips_is_bit_identical_with_and_without_the_loops():
    project = large_project(LargeSpec(8, 240, 30.0, 0, off_grid=True), seed=3)
    compiled = Mixer().render(project, 0.0, 30.0)
    expected = _numpy_form(lambda: Mixer().render(project, 0.0, 30.0))
    assert compiled.keys() == expected.keys()
    for name in compiled:
        assert np.array_equal(compiled[name], expected[name]), name
