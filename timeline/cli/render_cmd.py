"""`haptic-timeline render PROJECT -o OUT`: the mixed layers to CSV, NPZ or WAV."""

from __future__ import annotations

import argparse
import sys

from timeline.cli.options import add_range_options, parse_tracks
from timeline.layers_io import write_layers
from timeline.mixer import render
from timeline.projectfile import load


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("render", help="render the mixed layers to .csv, .npz or .wav")
    p.add_argument("project", help="a .htl project file")
    p.add_argument("-o", "--output", required=True, help="OUT.csv, OUT.npz or OUT.wav")
    add_range_options(p)
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    project = load(args.project)
    rate = project.rate if args.rate is None else args.rate
    start = args.start
    stop = project.duration if args.stop is None else args.stop
    layers = render(project, start, stop, rate, args.quality, parse_tracks(args.tracks))
    write_layers(layers, args.output, start, rate, project.axis)
    n = len(next(iter(layers.values()))) if layers else 0
    print(
        f"rendered {', '.join(layers) or 'no layers'}: {n} samples at {rate:g}/{project.unit} "
        f"({start:g} to {stop:g} {project.unit}, {args.quality}) -> {args.output}",
        file=sys.stderr,
    )
    return 0
