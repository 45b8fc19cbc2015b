"""`haptic-timeline export PROJECT -o OUT.ext`: a design to AHAP, .haptic, OTIO, .mat, CSV, WAV."""

from __future__ import annotations

import argparse
import sys
from typing import Any

from timeline.cli.options import positive


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "export",
        help="export a project to .ahap, .haptic, .otio, .mat, .csv, .txt, .wav, or firmware "
        "tables (.h, .json)",
    )
    p.add_argument("project", help="a .htl project file")
    p.add_argument(
        "-o",
        "--output",
        required=True,
        metavar="OUT.ext",
        help="the file to write; its extension picks the format",
    )
    p.add_argument(
        "--rate",
        type=positive,
        default=None,
        metavar="R",
        help="sample rate of the written layers (default: the project's; firmware tables: one "
        "entry per degree or per millisecond, end to end)",
    )
    p.add_argument(
        "--fixed-point",
        action="store_true",
        help="firmware tables (.h, .json) as int16 with a scale per table instead of float",
    )
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from timeline.files.exporting import export_project
    from timeline.files.projectfile import load
    from timeline.rendering.aliasing import aliasing_notes

    project = load(args.project)
    options: dict[str, Any] = {"fixed_point": True} if args.fixed_point else {}
    said = export_project(project, args.output, rate=args.rate, **options)
    for note in aliasing_notes(project, args.rate):
        print(f"haptic-timeline: warning: {note}", file=sys.stderr)
    print(f"exported {args.project} -> {args.output}" + (f": {said}" if said else ""),
          file=sys.stderr)  # fmt: skip
    return 0
