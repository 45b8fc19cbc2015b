"""Accumulation: amplitudes 1e-12..1e12 at 192 kHz against math.fsum, in chunks with bounded memory.

tests/core/test_extremes.py covers an hour at 10 kHz in chunks and 10,000 clips with gains
1e-6..1e6 at 10 kHz. Here the range is wider (gains 1e-12..1e12), the rate 192 kHz, and the
memory of a chunked render is bounded. Stated bounds: relative error <= 1e-12 of the sum of the
terms' magnitudes; traced peak memory <= 2 x the mixer's cache size + 8 chunk buffers.
"""

from __future__ import annotations

import tracemalloc

import pytest

from timeline.bench.accumulation import RATE, long_project, long_reference, overlapping
from timeline.rendering.mixer import Mixer

ERROR_BOUND = 1e-12
CACHE = 16 * 2**20


def test_ten_thousand_clips_from_1e_minus_12_to_1e12_match_fsum() -> None:
    worst, samples = overlapping(10_000)
    assert samples == round(0.3 * RATE)
    assert worst <= ERROR_BOUND


def chunked(seconds: float, chunk: float) -> tuple[float, int, int]:
    """Worst relative error at sampled points, samples rendered, traced peak bytes."""
    project = long_project(seconds)
    mixer = Mixer(cache_bytes=CACHE)
    worst, samples = 0.0, 0
    tracemalloc.start()
    try:
        for t0, layers in mixer.render_chunks(project, 0.0, seconds, RATE, chunk=chunk):
            out = layers["drive"]
            for i in range(0, len(out), 99_991):
                ref, scale = long_reference(t0 + i / RATE)
                worst = max(worst, abs(float(out[i]) - ref) / (scale or 1.0))
            samples += len(out)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    return worst, samples, peak


@pytest.mark.parametrize(
    "seconds", [30.0, pytest.param(3600.0, marks=pytest.mark.slow, id="an hour")]
)
def test_long_render_at_192khz_in_chunks_is_exact_and_bounded(seconds: float) -> None:
    chunk = 2.0
    worst, samples, peak = chunked(seconds, chunk)
    assert samples == round(seconds * RATE)
    assert worst <= ERROR_BOUND
    assert peak <= 2 * CACHE + 8 * chunk * RATE * 8
