"""Shared fixtures for the format tests: the corpus of real files, when present."""

from __future__ import annotations

from pathlib import Path

import pytest

CORPUS = Path(__file__).resolve().parents[3] / "shared" / "corpus"


@pytest.fixture
def corpus() -> Path:
    """The shared corpus of files made by other tools (skips when absent)."""
    if not CORPUS.is_dir():
        pytest.skip("the shared corpus is not present")
    return CORPUS
