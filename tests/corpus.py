"""Where the tests' files live: tests/data (hand-written, always present) and the shared corpus.

The shared corpus holds real files made by other tools (Lofelt's SDK test files, Lofelt Studio's
analysis of ten recordings); it is not part of the project. Tests read it from ../shared/corpus
beside the checkout or beside its folder of worktrees and skip without it. The environment
variable HAPTIC_TIMELINE_CORPUS names another folder; one that does not exist hides the corpus
(HAPTIC_TIMELINE_CORPUS=/nonexistent runs the suite as a checkout without it would).
"""

from __future__ import annotations

import os
from pathlib import Path

ENV = "HAPTIC_TIMELINE_CORPUS"
DATA = Path(__file__).resolve().parent / "data"
ROOT = DATA.parents[1]
ABSENT = f"the shared corpus is not present (../shared/corpus, or {ENV})"


def corpus_dir() -> Path | None:
    """The shared corpus: $HAPTIC_TIMELINE_CORPUS if set, else shared/corpus beside the
    repository or one of its parents; None when that folder does not exist."""
    override = os.environ.get(ENV)
    if override:
        folder = Path(override)
        return folder if folder.is_dir() else None
    for parent in (ROOT, *ROOT.parents):
        candidate = parent / "shared" / "corpus"
        if candidate.is_dir():
            return candidate
    return None
