"""Synthetic sounds with known envelopes and onsets, and the corpus pairs when present."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from timeline.bench.convert import PAIRS

CORPUS = PAIRS.parent  # the shared corpus, found by the benchmark that measures against it
RATE = 48_000


def tone_bursts(onsets: list[float], hz: float, length: float, rate: int = RATE) -> np.ndarray:
    """Decaying sine bursts (20 ms time constant) starting at the given times."""
    t = np.arange(int(length * rate)) / rate
    x = np.zeros_like(t)
    for start in onsets:
        after = t >= start
        dt = t[after] - start
        x[after] += np.sin(2 * np.pi * hz * dt) * np.exp(-dt / 0.02)
    return 0.8 * x


@pytest.fixture
def audio_pairs() -> Path:
    """The ten sounds with Lofelt Studio's analysis of each (skips when absent)."""
    folder = CORPUS / "audio-pairs"
    if not folder.is_dir():
        pytest.skip("the shared corpus is not present")
    return folder
