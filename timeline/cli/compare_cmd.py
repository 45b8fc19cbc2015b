"""`haptic-timeline compare A.htl B.htl ...`: perceptual distances between icons and their map.

One project alone compares its saved variants.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from timeline.signal.render_presets import DEFAULT_QUALITY, PRESETS


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("compare", help="perceptual distances between icons, and their 2-D map")
    p.add_argument("projects", nargs="+", help=".htl files (one file: its saved variants)")
    p.add_argument("--plot", help="write the map to this .png")
    p.add_argument("--json", action="store_true", help="print distances and map as JSON")
    p.add_argument("--quality", default=DEFAULT_QUALITY, choices=list(PRESETS))
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from timeline.files.projectfile import load
    from timeline.similarity.compare import compare
    from timeline.similarity.distance import ALIKE
    from timeline.similarity.icons import variant_icons

    projects = [(Path(path).stem, load(path)) for path in args.projects]
    icons = variant_icons(projects[0][1]) if len(projects) == 1 else projects
    result = compare(icons, args.quality)
    if args.json:
        print(json.dumps(result.as_dict(), indent=2))
    else:
        width = max(len(n) for n in result.names)
        print(" " * width + "  " + "  ".join(f"{n[:8]:>8}" for n in result.names) + "   [JND]")
        for name, row in zip(result.names, result.matrix, strict=True):
            print(f"{name:>{width}}  " + "  ".join(f"{v:8.2f}" for v in row))
        for a, b, d in result.too_alike():
            print(f"too alike: {a} and {b} are {d:.2f} JND apart (below {ALIKE:g})")
    if args.plot:
        from timeline.similarity.plot import plot_map

        plot_map(result, args.plot)
        print(f"map -> {args.plot}", file=sys.stderr)
    return 0
