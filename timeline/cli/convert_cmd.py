"""`haptic-timeline convert SOUND -o OUT.haptic|.ahap|.htl`: a sound to a haptic design."""

from __future__ import annotations

import argparse
import sys
from dataclasses import fields

from timeline.analysis.settings import AnalysisSettings
from timeline.cli.options import number


def _integer(text: str) -> int:
    try:
        return int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a whole number") from None


def add_settings_options(p: argparse.ArgumentParser) -> None:
    """One option per analysis setting (--attack, --sensitivity, --no-emphasis, ...)."""
    group = p.add_argument_group("analysis settings (defaults: Meta Haptics Studio's)")
    for f in fields(AnalysisSettings):
        flag = "--" + f.name.replace("_", "-")
        help_text = f"{AnalysisSettings.help(f.name)} (default: {f.default})".replace("%", "%%")
        if f.type in ("bool", bool):
            group.add_argument(flag, action=argparse.BooleanOptionalAction, default=None,
                               help=help_text)  # fmt: skip
        else:
            kind = _integer if f.type in ("int", int) else number
            group.add_argument(flag, type=kind, default=None, metavar="N", help=help_text)


def settings_from(args: argparse.Namespace) -> AnalysisSettings:
    """The analysis settings given on the command line (the rest at their defaults)."""
    given = {f.name: getattr(args, f.name) for f in fields(AnalysisSettings)}
    return AnalysisSettings(**{k: v for k, v in given.items() if v is not None})


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "convert",
        help="analyse a sound into a haptic design (.haptic, .ahap, or a .htl project)",
        description="Analyse a sound file (WAV, FLAC, OGG, AIFF, ...) into amplitude and "
        "frequency envelopes and emphasis. A .htl project also keeps the sound on an audio "
        "track; the design stays editable as envelope breakpoints and emphasis points.",
    )
    p.add_argument("sound", help="the sound file to analyse")
    p.add_argument("-o", "--output", required=True, metavar="OUT.ext",
                   help="the file to write: .haptic, .ahap or .htl")  # fmt: skip
    add_settings_options(p)
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from timeline.files.convert import convert_file

    project = convert_file(args.sound, args.output, settings_from(args))
    print(f"converted {args.sound} -> {args.output} ({project.duration:.3f} s)", file=sys.stderr)
    return 0
