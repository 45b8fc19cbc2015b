"""The direct windowed-sinc upsampling sums each knot of its table once and interpolates between
knots: the values of the per-output sum it replaced, and of the windowed sincs summed exactly."""

from __future__ import annotations

import math

import numpy as np
import pytest

from timeline.signal import resample
from timeline.signal.render_presets import preset

HALF = 32  # taps either side
BETA = 9.0  # the Kaiser window's


def _windowed_sinc(d: np.ndarray) -> np.ndarray:
    r = d / HALF
    return np.sinc(d) * np.i0(BETA * np.sqrt(np.clip(1.0 - r * r, 0.0, None))) / np.i0(BETA)


def _before(data: np.ndarray, start: float, step: float, n: int) -> np.ndarray:
    """The code replaced: each output's 64 taps interpolated in the table, then summed."""
    distances = np.linspace(-HALF, HALF, 2**18 + 1)
    table = _windowed_sinc(distances)
    out = np.zeros(n)
    first = max(0, math.ceil((-HALF - start) / step))
    last = min(n, math.floor((len(data) - 1 + HALF - start) / step) + 1)
    k = np.arange(-HALF + 1, HALF + 1)
    for lo in range(first, last, 2**13):
        x = start + step * np.arange(lo, min(lo + 2**13, last))
        base = np.floor(x).astype(np.int64)
        index = base[:, None] + k[None, :]
        taps = np.interp(x[:, None] - index, distances, table)
        inside = (index >= 0) & (index < len(data))
        values = np.where(inside, data[np.clip(index, 0, len(data) - 1)], 0.0)
        out[lo : lo + len(x)] = np.einsum("ij,ij->i", taps, values)
    return out


def _exact(data: np.ndarray, start: float, step: float, n: int) -> np.ndarray:
    """The same band-limited reconstruction with exact taps: sample j weighs the windowed sinc
    at x - j, for x - j from -HALF up to HALF."""
    x = start + step * np.arange(n)
    d = x[:, None] - np.arange(len(data))[None, :]
    weights = np.where((d >= -HALF) & (d < HALF), _windowed_sinc(d), 0.0)
    return weights @ data


# (upsampling ratio, source samples, first output's source index): odd lengths, 1 and 2 samples,
# starts on and off the grid, before the samples (outputs out of reach) and across them
CASES = [
    (1.5, 1, -40.3),
    (1.5, 17, 0.0),
    (10.0, 2, -33.37),
    (10.0, 9, 3.25),
    (1000.0, 1, -0.61),
    (1000.0, 2, 0.123456789),
    (1000.0, 33, 14.9),
    (4096.5, 65, 31.999),
    (1e7, 1, -1e-4),
    (1e7, 2, 1.0 - 3e-5),
    (1e7, 7, -32.0 - 1e-4),
]


@pytest.mark.parametrize(("ratio", "length", "start"), CASES)
def test_the_upsampling_gives_the_per_output_sums_within_1e_12_of_full_scale(
    ratio: float, length: int, start: float, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(resample, "_UPSAMPLE_CHUNK", 700)  # several passes, their seams inside
    data = np.random.default_rng(length).uniform(-1.0, 1.0, length)
    step = 1.0 / ratio
    n = min(3_000, math.ceil((length + 2 * HALF) / step))
    new = resample._sinc_upsample(data, start, step, n)
    old = _before(data, start, step, n)
    assert np.abs(new - old).max() <= 1e-12 * np.abs(data).max()
    assert np.array_equal(new == 0.0, old == 0.0)  # zero out of the filter's reach, as before
    assert np.abs(new - _exact(data, start, step, n)).max() < 1e-6  # the table's own error


def test_a_2_value_recording_at_0_001_hz_renders_the_windowed_sincs_at_10_khz() -> None:
    """The campaign's 2,000 s clip, read near its second sample (one of 20 million outputs)."""
    data = np.array([0.5, -0.5], dtype=np.float32)
    u0 = 999.9  # s: outputs from 0.1 s before the second sample to 0.1 s after it
    values = resample.sample_grid(data, 0.001, u0, 1e-4, 2_001, preset("normal"))
    exact = _exact(data.astype(np.float64), u0 * 0.001, 1e-7, 2_001)
    assert np.abs(values - exact).max() < 1e-6 and values[1_000] == pytest.approx(-0.5, abs=1e-6)
