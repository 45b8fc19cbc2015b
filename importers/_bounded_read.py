"""Read a whole file no larger than a limit, refused by its size before anything is read."""

from __future__ import annotations

from pathlib import Path

from timeline.plugins.file_formats import FormatError


def read_at_most(path: Path, limit: int, too_large: FormatError) -> bytes:
    """The file's bytes, or `too_large` raised when it holds more than `limit` bytes (judged by
    its size first, and again by what was read, should it have grown meanwhile)."""
    size = path.stat().st_size
    if size > limit:
        raise too_large
    with path.open("rb") as file:
        # read(n) allocates n bytes up front: ask for the size judged (+1 sees a file that grew)
        raw = file.read(size + 1)
    if len(raw) > limit:
        raise too_large
    return raw
