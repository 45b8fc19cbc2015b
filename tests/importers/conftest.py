"""Shared fixtures for the format tests: the corpus of real files, when present."""

from __future__ import annotations

from pathlib import Path

import pytest


def _find_corpus() -> Path:
    """../shared/corpus beside the repository (or beside the folder of git worktrees)."""
    for folder in Path(__file__).resolve().parents[2:]:
        if (folder / "shared" / "corpus").is_dir():
            return folder / "shared" / "corpus"
    return Path(__file__).resolve().parents[3] / "shared" / "corpus"


CORPUS = _find_corpus()


@pytest.fixture
def corpus() -> Path:
    """The shared corpus of files made by other tools (skips when absent)."""
    if not CORPUS.is_dir():
        pytest.skip("the shared corpus is not present")
    return CORPUS
