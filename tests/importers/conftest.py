"""Shared fixtures for the format tests: the corpus of real files, when present."""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.corpus import ABSENT, corpus_dir

CORPUS = corpus_dir()


@pytest.fixture
def corpus() -> Path:
    """The shared corpus of files made by other tools (skips when absent)."""
    if CORPUS is None:
        pytest.skip(ABSENT)
    return CORPUS
