"""`haptic-timeline bench`: measure speed against accuracy; print tables, write plots."""

from __future__ import annotations

import argparse
import time
from pathlib import Path

from timeline.errors import HapticTimelineError


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "bench",
        help="run the benchmarks (mixer, quality presets, resamplers, simulator, extremes)",
        description="Print benchmark tables and write plots (PNG). Never fails on a time.",
    )
    p.add_argument("which", nargs="*", metavar="WHICH", help="benchmarks to run (default: all)")
    p.add_argument("--quick", action="store_true", help="smaller sizes, well under 2 minutes (CI)")
    p.add_argument("--out", type=Path, default=Path("bench-results"),
                   help="directory for plots and tables (default: bench-results)")  # fmt: skip
    p.add_argument("--list", action="store_true", help="list the benchmarks and exit")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from timeline.bench import MODULES, benchmarks

    if args.list:
        for name, module in benchmarks().items():
            print(f"{name:14} {module.SUMMARY}")
        return 0
    unknown = [w for w in args.which if w not in MODULES]
    if unknown:
        raise HapticTimelineError(
            f"there is no benchmark {unknown[0]!r} (choose from {', '.join(MODULES)})"
        )
    found = benchmarks(args.which)
    chosen = args.which or list(found)
    args.out.mkdir(parents=True, exist_ok=True)
    report = []
    for name in chosen:
        start = time.perf_counter()
        tables = found[name].run(args.quick, args.out)
        for table in tables:
            print(table.text(), end="\n\n", flush=True)
            report.append(table.text())
        print(f"({name}: {time.perf_counter() - start:.1f} s)\n", flush=True)
    (args.out / "tables.md").write_text("\n\n".join(report) + "\n")
    print(f"plots and tables.md in {args.out}")
    return 0
