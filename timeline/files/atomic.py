"""Atomic file writes: the old file stays intact until the new one is complete and synced.

The temporary is named `.NAME.partial-PID-RANDOM.EXT` beside the target. A process killed
mid-write cannot remove its own temporary, so every write first removes the leftovers in that
folder whose writing process no longer exists.
"""

from __future__ import annotations

import contextlib
import os
import re
import tempfile
from collections.abc import Callable
from pathlib import Path

PARTIAL = ".partial-"  # marks a temporary: .NAME.partial-PID-RANDOM.EXT
_WRITER = re.compile(r"\.partial-(\d+)-")


def write_atomically(path: str | os.PathLike, write: Callable[[Path], None]) -> None:
    """Call write(a temporary path beside `path`), sync it, and rename it onto `path`.

    The temporary keeps the target's extension (writers that pick a format by it still work),
    the new file keeps the old one's permissions, and any failure removes the temporary.
    """
    path = Path(path)
    folder = path.parent if str(path.parent) else Path(".")
    remove_leftovers(folder)
    prefix = f".{path.stem}{PARTIAL}{os.getpid()}-"
    fd, name = tempfile.mkstemp(prefix=prefix, suffix=path.suffix, dir=folder)
    os.close(fd)
    tmp = Path(name)
    try:
        os.chmod(tmp, file_mode(path))
        write(tmp)
        _fsync(tmp, os.O_RDONLY)
        os.replace(tmp, path)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise
    with contextlib.suppress(OSError):  # some file systems cannot sync a folder
        _fsync(folder, os.O_RDONLY)


def remove_leftovers(folder: Path) -> list[Path]:
    """Remove temporaries that killed writers left in `folder`; returns what was removed."""
    removed = []
    try:
        names = [p for p in folder.iterdir() if p.name.startswith(".") and PARTIAL in p.name]
    except OSError:
        return removed
    for leftover in names:
        match = _WRITER.search(leftover.name)
        if match and not _alive(int(match.group(1))):
            with contextlib.suppress(OSError):
                leftover.unlink()
                removed.append(leftover)
    return removed


def _alive(pid: int) -> bool:
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OverflowError):
        return pid > 0
    return True


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


def file_mode(path: str | os.PathLike) -> int:
    """An existing file's permissions; for a new file the usual 0666 less the umask (what a
    temporary file made by `tempfile`, always 0600, is given before it replaces `path`)."""
    path = Path(path)
    try:
        return path.stat().st_mode & 0o777
    except OSError:
        umask = os.umask(0)
        os.umask(umask)
        return 0o666 & ~umask
