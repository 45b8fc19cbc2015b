"""Atomic file writes: the old file stays intact until the new one is complete and synced."""

from __future__ import annotations

import contextlib
import os
import tempfile
from collections.abc import Callable
from pathlib import Path


def write_atomically(path: str | os.PathLike, write: Callable[[Path], None]) -> None:
    """Call write(a temporary path beside `path`), sync it, and rename it onto `path`.

    The temporary keeps the target's extension (writers that pick a format by it still work),
    the new file keeps the old one's permissions, and any failure removes the temporary.
    """
    path = Path(path)
    folder = path.parent if str(path.parent) else Path(".")
    fd, name = tempfile.mkstemp(prefix=f".{path.stem}.", suffix=path.suffix, dir=folder)
    os.close(fd)
    tmp = Path(name)
    try:
        os.chmod(tmp, _file_mode(path))
        write(tmp)
        _fsync(tmp, os.O_RDONLY)
        os.replace(tmp, path)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise
    with contextlib.suppress(OSError):  # some file systems cannot sync a folder
        _fsync(folder, os.O_RDONLY)


def check_target(path: str | os.PathLike) -> None:
    """Raise one sentence if a file cannot be written at `path` (checked before slow work)."""
    from timeline.errors import HapticTimelineError

    path = Path(path)
    folder = path.parent if str(path.parent) else Path(".")
    if path.is_dir():
        raise HapticTimelineError(f"cannot write {path}: it is a folder")
    if not folder.is_dir():
        raise HapticTimelineError(f"cannot write {path}: the folder {folder} does not exist")
    if not os.access(folder, os.W_OK):
        raise HapticTimelineError(f"cannot write {path}: the folder {folder} is not writable")


def _fsync(path: Path, flags: int) -> None:
    fd = os.open(path, flags)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)


def _file_mode(path: Path) -> int:
    """An existing file's permissions; for a new file the usual 0666 less the umask."""
    try:
        return path.stat().st_mode & 0o777
    except OSError:
        umask = os.umask(0)
        os.umask(umask)
        return 0o666 & ~umask
