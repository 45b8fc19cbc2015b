"""`haptic-timeline export PROJECT -o OUT.ext`: a design to AHAP, .haptic, OTIO, .mat, CSV, WAV."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from timeline.cli.units import axis_rate, rate_on_axis
from timeline.errors import HapticTimelineError

FIRMWARE_TABLES = (".h", ".json")
# Designs in seconds: vibration on a time axis, which a position project does not have.
TIME_DESIGNS = {".ahap": "AHAP", ".haptic": "a .haptic file"}


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
        type=axis_rate,
        default=None,
        metavar="R",
        help="sample rate of the written layers: samples per second, or per degree on a "
        "position project; 5730/rad also (default: the project's; firmware tables: one entry "
        "per degree or per millisecond, end to end); for .otio and .otioz the edit's frame "
        "rate (24, 25, 30, 23.976, ...), for video editors' tools",
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
    from timeline.plugins.file_formats import writer_for
    from timeline.rendering.aliasing import aliasing_notes

    suffix = Path(args.output).suffix.lower()
    if args.fixed_point and suffix not in FIRMWARE_TABLES:
        raise HapticTimelineError(
            f"--fixed-point applies to firmware tables (.h, .json), not to a "
            f"{suffix or 'file without an extension'}"
        )
    project = load(args.project)
    if project.axis == "position" and suffix in TIME_DESIGNS:
        raise HapticTimelineError(
            f"{TIME_DESIGNS[suffix]} is vibration over time, and {Path(args.project).name} is a "
            "position project with no time axis: export its tables (.h, .json) or layers "
            "(.csv, .mat) instead"
        )
    rate = None if args.rate is None else rate_on_axis(args.rate, project.axis)
    options: dict[str, Any] = {"fixed_point": True} if args.fixed_point else {}
    said = export_project(project, args.output, rate=rate, **options)
    frames = writer_for(args.output).name == "otio"  # a frame rate: nothing is resampled
    for note in [] if frames else aliasing_notes(project, rate):
        print(f"haptic-timeline: warning: {note}", file=sys.stderr)
    print(f"exported {args.project} -> {args.output}" + (f": {said}" if said else ""),
          file=sys.stderr)  # fmt: skip
    return 0
