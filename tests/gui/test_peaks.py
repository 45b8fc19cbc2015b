"""Peak pyramids: column summaries equal a direct min/max over the blocks they cover."""

from __future__ import annotations

import numpy as np
import pytest

from timeline.gui.peaks import PeakPyramid


def _direct(data: np.ndarray, pyramid: PeakPyramid, first: float, last: float, count: int):
    """Min/max per column straight from the samples, over the same blocks the pyramid uses."""
    per_column = (last - first) / count
    block = 1
    for size, _, _ in pyramid.levels:
        if size * 2 > per_column:
            break
        block = size
    blocks = -(-len(data) // block)
    edges = np.linspace(first, last, count + 1)
    starts = np.clip(np.floor(edges[:-1] / block).astype(np.int64), 0, blocks - 1)
    stop = max(int(np.clip(np.ceil(last / block), 1, blocks)), int(starts[-1]) + 1)
    following = np.maximum(np.r_[starts[1:], stop], starts + 1)
    stops = starts + 1 if per_column < block else following
    lo = [data[a * block : z * block].min() for a, z in zip(starts, stops, strict=True)]
    hi = [data[a * block : z * block].max() for a, z in zip(starts, stops, strict=True)]
    return np.array(lo), np.array(hi)


@pytest.mark.parametrize("n", [7, 33, 1000, 100_003])
def test_columns_match_a_direct_min_max_at_every_zoom(n):
    rng = np.random.default_rng(n)
    data = np.cumsum(rng.standard_normal(n))
    pyramid = PeakPyramid(data)
    for first, last, count in [
        (0.0, n, 50),
        (0.0, n, 3),
        (n * 0.25, n * 0.5, 400),  # zoomed in: the last column ends well before the data
        (n * 0.1, n * 0.1 + 5, 5),
        (n * 0.9, n * 1.2, 17),
        (1.5, 2.5, 800),  # less than one sample per column
    ]:
        lo, hi = pyramid.columns(first, last, count)
        want_lo, want_hi = _direct(data, pyramid, first, last, count)
        rounded = pyramid.levels and any(
            size * 2 <= (last - first) / count for size, *_ in pyramid.levels
        )
        cast = np.float32 if rounded else np.float64
        np.testing.assert_array_equal(lo, want_lo.astype(cast))
        np.testing.assert_array_equal(hi, want_hi.astype(cast))


def test_the_samples_are_referenced_and_the_levels_are_compact():
    data = np.sin(np.arange(1_000_000) * 0.001)
    pyramid = PeakPyramid(data)
    assert pyramid.data is data
    level_bytes = sum(lo.nbytes + hi.nbytes for _, lo, hi in pyramid.levels)
    assert level_bytes < data.nbytes / 7
    lo, hi = pyramid.columns(0, len(data), 10)
    assert lo.min() == pytest.approx(-1.0, abs=1e-6) and hi.max() == pytest.approx(1.0, abs=1e-6)


def test_the_first_level_is_built_in_chunks_from_float32_samples(monkeypatch):
    from timeline.gui import peaks

    monkeypatch.setattr(peaks, "CHUNK", 4 * peaks.BASE)
    n = 12 * peaks.BASE + 37  # three chunks and a partial last block
    data = np.random.default_rng(3).standard_normal(n).astype(np.float32)
    block, lo, hi = PeakPyramid(data).levels[0]
    assert block == peaks.BASE and lo.dtype == np.float32
    starts = range(0, n, block)
    np.testing.assert_array_equal(lo, [data[a : a + block].min() for a in starts])
    np.testing.assert_array_equal(hi, [data[a : a + block].max() for a in starts])
