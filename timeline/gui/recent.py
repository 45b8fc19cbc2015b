"""The recent-files list, kept in the user data directory."""

from __future__ import annotations

import json
from pathlib import Path

from .autosave import data_dir

LIMIT = 10


def recent_files() -> list[Path]:
    """Recently opened or saved projects, newest first (missing files left out)."""
    try:
        names = json.loads((data_dir() / "recent.json").read_text())
    except (OSError, ValueError):
        return []
    return [Path(n) for n in names if isinstance(n, str) and Path(n).exists()]


def remember(path: Path) -> None:
    """Put a project at the top of the recent list."""
    names = [str(path.resolve())] + [
        str(p) for p in recent_files() if p.resolve() != path.resolve()
    ]
    (data_dir() / "recent.json").write_text(json.dumps(names[:LIMIT]))
