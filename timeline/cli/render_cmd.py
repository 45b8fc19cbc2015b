"""`haptic-timeline render PROJECT -o OUT`: the mixed layers to CSV, WAV, MAT or NPZ."""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path
from typing import TYPE_CHECKING

from timeline.cli.options import add_range_options, parse_tracks
from timeline.cli.units import amount, on_axis, rate_on_axis, rate_text
from timeline.errors import HapticTimelineError

if TYPE_CHECKING:  # numpy and the mixer load when something is rendered, not for --help
    from timeline.model import Project


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("render", help="render the mixed layers to .csv, .wav, .mat or .npz")
    p.add_argument("project", help="a .htl project file")
    p.add_argument("-o", "--output", required=True, help="OUT.csv, OUT.wav, OUT.mat or OUT.npz")
    add_range_options(p)
    p.set_defaults(func=run)


def render_range(project: Project, args: argparse.Namespace) -> tuple[float, float, float]:
    """--start, --stop and --rate in axis units (s or rad), or one sentence in the units typed."""
    from timeline.rendering.mixer import MAX_SAMPLES

    axis = project.axis
    start = 0.0 if args.start is None else on_axis(args.start, axis, "--start")
    stop = project.duration if args.stop is None else on_axis(args.stop, axis, "--stop")
    rate = project.rate if args.rate is None else rate_on_axis(args.rate, axis)
    if axis == "time" and start < 0:
        raise HapticTimelineError(
            f"--start {amount(start, axis)} is before the timeline starts (0 s)"
        )
    if stop < start:
        raise HapticTimelineError(
            f"the render stops ({amount(stop, axis)}) before it starts ({amount(start, axis)})"
        )
    count = (stop - start) * rate  # an uncountable one: the mixer's sentence
    if math.isfinite(count) and count > MAX_SAMPLES:
        raise HapticTimelineError(
            f"{amount(start, axis)} to {amount(stop, axis)} at {rate_text(rate, axis)} is more "
            f"than one render holds ({MAX_SAMPLES} samples): render a shorter range or at a "
            "lower --rate"
        )
    return start, stop, rate


def run(args: argparse.Namespace) -> int:
    from timeline.files.exporting import write_layers
    from timeline.files.projectfile import load
    from timeline.plugins.file_formats import Layers
    from timeline.rendering.aliasing import aliasing_notes
    from timeline.rendering.mixer import render

    project = load(args.project)
    start, stop, rate = render_range(project, args)
    columns = render(project, start, stop, rate, args.quality, parse_tracks(args.tracks))
    for note in aliasing_notes(project, rate):
        print(f"haptic-timeline: warning: {note}", file=sys.stderr)
    if not columns:
        raise HapticTimelineError("the project has no layers to render (no clips, or all muted)")
    layers = Layers(columns, rate, start, project.axis)
    output = Path(args.output)
    write_layers(layers, output)
    print(
        f"rendered {', '.join(columns)}: {layers.length} samples, {amount(start, project.axis)} "
        f"to {amount(stop, project.axis)} at {rate_text(rate, project.axis)}, {args.quality} "
        f"-> {args.output}",
        file=sys.stderr,
    )
    return 0
