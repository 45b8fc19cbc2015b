"""`haptic-timeline import FILE --into PROJECT`: a recording or design onto a track."""

from __future__ import annotations

import argparse
import sys
import time
from typing import TextIO

from timeline.cli.notes import print_notes
from timeline.cli.options import number, positive
from timeline.cli.units import amount, axis_value, positive_axis_value
from timeline.plugins.track_kinds import DEFAULT_KIND


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "import", help="import audio, CSV/TXT, .mat, AHAP, .haptic or .otio into a project"
    )
    p.add_argument("file", help="the file to import")
    p.add_argument(
        "--into",
        required=True,
        metavar="PROJECT",
        help="a .htl project file (created on the time axis at 10 kHz if missing)",
    )
    p.add_argument(
        "--track",
        default=None,
        metavar="KIND",
        help=f"track kind for a tile (default {DEFAULT_KIND}); the first such track",
    )
    p.add_argument("--at", type=axis_value, default=None, metavar="WHERE",
                   help="where the import starts: seconds, or degrees on a position project "
                   "(default 0)")  # fmt: skip
    p.add_argument("--length", type=positive_axis_value, default=None, metavar="SPAN",
                   help="stretch the import to this span: seconds, or degrees on a position "
                   "project (default: its own length; a second of a recording is a radian on a "
                   "position project)")  # fmt: skip
    p.add_argument("--gain", type=number, default=1.0, metavar="G", help="clip gain")
    p.add_argument(
        "--channel",
        default=None,
        metavar="N|mix",
        help="audio channel from 1, or mix (the mean; default)",
    )
    p.add_argument(
        "--column",
        default=None,
        metavar="NAME",
        help="CSV/TXT column or .mat variable (default: first after time)",
    )
    p.add_argument(
        "--rate",
        type=positive,
        default=None,
        metavar="R",
        help="sample rate of a file without a time column",
    )
    p.set_defaults(func=run)


class ProgressBar:
    """A one-line progress bar on a stream, shown only once a read has taken half a second."""

    def __init__(self, label: str, stream: TextIO | None = None, delay: float = 0.5) -> None:
        # sys.stderr as it is now, not as it was when this module was imported
        self.label, self.stream, self.delay = label, stream or sys.stderr, delay
        self.started = time.monotonic()
        self.shown = False

    def __call__(self, fraction: float) -> None:
        if not self.shown and time.monotonic() - self.started < self.delay:
            return
        self.shown = True
        filled = int(30 * min(max(fraction, 0.0), 1.0))
        bar = "#" * filled + "-" * (30 - filled)
        self.stream.write(f"\r{self.label} [{bar}] {100 * fraction:5.1f}%")
        self.stream.flush()

    def close(self) -> None:
        if self.shown:
            self.stream.write("\n")


def run(args: argparse.Namespace) -> int:
    from timeline.cli.import_axis import Arrangement, check_project_path
    from timeline.files.importing import import_into_project_file

    check_project_path(args.into)
    arrangement = Arrangement(args)
    bar = ProgressBar(f"importing {args.file}")
    try:
        clip_ids, notes = import_into_project_file(
            args.file,
            args.into,
            kind=args.track,
            arrange=arrangement,
            gain=args.gain,
            channel=args.channel,
            column=args.column,
            rate=args.rate,
            progress=bar,
        )
    finally:
        bar.close()
    print(
        f"imported {args.file} into {args.into}: {len(clip_ids)} clip(s) at "
        f"{amount(arrangement.at, arrangement.axis)}",
        file=sys.stderr,
    )
    print_notes(notes)
    return 0
