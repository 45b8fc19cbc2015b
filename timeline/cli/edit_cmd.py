"""`haptic-timeline edit [PROJECT]`: open the editor (a new project is created on first save)."""

from __future__ import annotations

import argparse
import os
import sys

from timeline.errors import HapticTimelineError


def add_parser(subparsers: argparse._SubParsersAction) -> None:
    """Register the edit verb."""
    parser = subparsers.add_parser("edit", help="open the editor on a project")
    parser.add_argument("project", nargs="?", help="a .htl project (created on save if missing)")
    parser.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    """Open the editor; without a display, say so in one sentence."""
    if sys.platform.startswith("linux") and not (
        os.environ.get("DISPLAY")
        or os.environ.get("WAYLAND_DISPLAY")
        or os.environ.get("QT_QPA_PLATFORM")
    ):
        raise HapticTimelineError(
            "there is no display to open the editor on; use `haptic-timeline play PROJECT` instead"
        )
    try:
        from timeline.gui.app import run as run_editor
    except ImportError as exc:
        raise HapticTimelineError(f"the editor needs PySide6 ({exc})") from None
    return run_editor(args.project)
