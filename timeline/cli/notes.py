"""Readers' notes on the command line: one line each on stderr (used by `import` and `convert`)."""

from __future__ import annotations

import sys
from collections.abc import Iterable
from typing import TextIO


def print_notes(notes: Iterable[str], stream: TextIO | None = None) -> None:
    """Print each note (what a reader assumed, clamped or skipped) as one `note: ...` line."""
    stream = sys.stderr if stream is None else stream
    for note in notes:
        print("note: " + " ".join(str(note).split()), file=stream)
