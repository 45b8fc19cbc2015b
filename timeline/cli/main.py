"""Entry point of the `haptic-timeline` command: parses the verb and reports user errors."""

from __future__ import annotations

import argparse
import difflib
import importlib
import os
import sys
from pathlib import Path

from timeline.errors import HapticTimelineError

# Each verb module defines add_parser(subparsers) which sets `func` on its parser.
VERB_MODULES = [
    "timeline.cli.edit_cmd",
    "timeline.cli.render_cmd",
    "timeline.cli.info_cmd",
    "timeline.cli.play_cmd",
    "timeline.cli.devices_cmd",
    "timeline.cli.import_cmd",
    "timeline.cli.export_cmd",
    "timeline.cli.convert_cmd",
    "timeline.cli.bench_cmd",
    "timeline.cli.check_cmd",
    "timeline.cli.compare_cmd",
]


def _verb_of(module: str) -> str:
    """The verb a verb module defines: timeline.cli.render_cmd defines `render`."""
    return module.rsplit(".", 1)[1].removesuffix("_cmd")


VERBS = {_verb_of(name): name for name in VERB_MODULES}


def build_parser(verb: str | None = None) -> argparse.ArgumentParser:
    """The command line's parser: every verb, or only `verb` (the others' modules stay unloaded)."""
    parser = argparse.ArgumentParser(
        prog="haptic-timeline",
        description="Design haptic icons on a multitrack timeline.",
    )
    sub = parser.add_subparsers(dest="verb", metavar="VERB")
    for name in [VERBS[verb]] if verb in VERBS else VERB_MODULES:
        importlib.import_module(name).add_parser(sub)
    return parser


def _with_default_verb(argv: list[str], verbs: set[str]) -> list[str]:
    """`haptic-timeline` and `haptic-timeline PROJECT` open the editor, like `edit`.

    A first word that is neither a verb nor a file name (no extension, no folder, not an
    existing file) is a mistyped verb: HapticTimelineError names the verbs.
    """
    if not argv:
        return ["edit"]
    first = argv[0]
    if first in verbs or first.startswith("-"):
        return argv
    if Path(first).suffix or os.sep in first or Path(first).exists():
        return ["edit", *argv]
    close = difflib.get_close_matches(first, sorted(verbs), n=1)
    hint = f"did you mean {close[0]!r}? " if close else ""
    raise HapticTimelineError(
        f"unknown verb {first!r} ({hint}verbs: {', '.join(sorted(verbs))}; "
        "a project to open ends in .htl)"
    )


def one_blas_thread() -> None:
    """Hold OpenBLAS to one thread unless the user chose otherwise (before numpy loads).

    Every matrix the project factors or multiplies is tiny (the servo loop's 3x3 to 40x40), and
    the mixer uses no BLAS; worker threads only spin against the mixer and the simulator. On this
    2-core machine under load a 3x3 expm took up to 20 ms with the pool (0.04 ms alone), and the
    simulator's stability flags were 150x slower.
    """
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")


def out_of_memory(args: argparse.Namespace) -> str:
    """What running out of memory means for the verb: a file too large to read, or a range."""
    source = getattr(args, "file", None) or getattr(args, "sound", None)
    if source:
        return f"ran out of memory reading {source}: it needs more memory than is free"
    return "ran out of memory; try a shorter range or a lower rate"


def main(argv: list[str] | None = None) -> int:
    """Run one verb; a user's mistake prints one sentence on stderr and returns non-zero."""
    one_blas_thread()
    try:
        argv = _with_default_verb(sys.argv[1:] if argv is None else argv, set(VERBS))
    except HapticTimelineError as exc:
        print(f"haptic-timeline: {exc}", file=sys.stderr)
        return 2
    args = build_parser(argv[0]).parse_args(argv)
    if not getattr(args, "func", None):
        build_parser().print_help()
        return 2
    try:
        return int(args.func(args) or 0)
    except HapticTimelineError as exc:
        print(f"haptic-timeline: {exc}", file=sys.stderr)
        return 1
    except BrokenPipeError:
        # The reader went away (e.g. `| head`): stop quietly, as other command-line tools do.
        sys.stdout = open(os.devnull, "w")  # noqa: SIM115 - replaces the closed stream for exit
        return 0
    except OSError as exc:
        where = f" ({exc.filename})" if exc.filename else ""
        print(f"haptic-timeline: {exc.strerror or exc}{where}", file=sys.stderr)
        return 1
    except MemoryError:
        print(f"haptic-timeline: {out_of_memory(args)}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print("haptic-timeline: interrupted", file=sys.stderr)
        return 130


if __name__ == "__main__":
    sys.exit(main())
