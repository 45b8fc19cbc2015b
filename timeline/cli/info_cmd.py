"""`haptic-timeline info PROJECT [--json]`: what a project holds."""

from __future__ import annotations

import argparse
import json


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("info", help="describe a project: tracks, clips, duration, layers, variants")
    p.add_argument("project", help="a .htl project file")
    p.add_argument("--json", action="store_true", help="print JSON")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from timeline.files.projectfile import load
    from timeline.files.summary import describe, summary

    project = load(args.project)
    print(json.dumps(summary(project), indent=2) if args.json else describe(project))
    return 0
