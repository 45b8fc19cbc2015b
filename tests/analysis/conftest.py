"""Synthetic sounds with known envelopes and onsets, and the corpus pairs when present."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from tests.corpus import corpus_dir
from timeline.bench import convert

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
def audio_pairs(monkeypatch: pytest.MonkeyPatch) -> Path:
    """The ten sounds with Lofelt Studio's analysis of each, from the shared corpus (skips when
    absent). No stand-in: the test is of agreement with those recordings and that analysis,
    which are not the project's to redistribute (non-commercial licence)."""
    corpus = corpus_dir()
    if corpus is None or not (corpus / "audio-pairs").is_dir():
        pytest.skip("needs the corpus's recordings and Lofelt Studio's analysis (not ours to ship)")
    folder = corpus / "audio-pairs"
    monkeypatch.setattr(convert, "PAIRS", folder)  # the benchmark's tables read the same folder
    return folder
