"""`haptic-timeline render PROJECT -o OUT`: the mixed layers to CSV, WAV, MAT or NPZ."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from timeline.cli.options import add_range_options, parse_tracks
from timeline.errors import HapticTimelineError


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("render", help="render the mixed layers to .csv, .wav, .mat or .npz")
    p.add_argument("project", help="a .htl project file")
    p.add_argument("-o", "--output", required=True, help="OUT.csv, OUT.wav, OUT.mat or OUT.npz")
    add_range_options(p)
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from timeline.files.exporting import write_layers
    from timeline.files.projectfile import load
    from timeline.plugins.file_formats import Layers
    from timeline.rendering.aliasing import aliasing_notes
    from timeline.rendering.mixer import render

    project = load(args.project)
    rate = project.rate if args.rate is None else args.rate
    start = args.start
    stop = project.duration if args.stop is None else args.stop
    columns = render(project, start, stop, rate, args.quality, parse_tracks(args.tracks))
    for note in aliasing_notes(project, rate):
        print(f"haptic-timeline: warning: {note}", file=sys.stderr)
    if not columns:
        raise HapticTimelineError("the project has no layers to render (no clips, or all muted)")
    layers = Layers(columns, rate, start, project.axis)
    output = Path(args.output)
    write_layers(layers, output)
    print(
        f"rendered {', '.join(columns)}: {layers.length} samples at {rate:g}/{project.unit} "
        f"({start:g} to {stop:g} {project.unit}, {args.quality}) -> {args.output}",
        file=sys.stderr,
    )
    return 0
