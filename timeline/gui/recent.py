"""The recent-files list, kept in the application's QSettings (organisation and app name)."""

from __future__ import annotations

from pathlib import Path

from PySide6.QtCore import QSettings

KEY = "recent_files"
LIMIT = 10


def recent_files() -> list[Path]:
    """Recently opened or saved projects, newest first (missing files left out)."""
    names = QSettings().value(KEY, [], type=list)
    if not isinstance(names, list):
        return []
    return [Path(n) for n in names if isinstance(n, str) and Path(n).exists()]


def remember(path: Path) -> None:
    """Put a project at the top of the recent list."""
    path = path.resolve()
    names = [str(path)] + [str(p) for p in recent_files() if p.resolve() != path]
    settings = QSettings()
    settings.setValue(KEY, names[:LIMIT])
    settings.sync()
