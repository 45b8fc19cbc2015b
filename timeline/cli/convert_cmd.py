"""`haptic-timeline convert SOUND... -o OUT`: sounds to haptic designs, one or a whole library.

One sound and an output file (`-o OUT.haptic|.ahap|.htl`) writes that file. Several sounds, or
folders of them, and an output folder (`-o DIR`, made if missing) write one design each
(`DIR/<name>.<--format>`), in one process over a pool of worker processes (`--jobs`, default: one
per core), with a progress bar on a terminal. The design's level is staged for the device
(`--gain auto`, the default: within its limit, and raised when no hand would feel it clearly) or
given in dB (`--gain -6`); notes say what was done.
"""

from __future__ import annotations

import argparse
import os
import sys
from dataclasses import fields
from pathlib import Path
from typing import TYPE_CHECKING

from timeline.analysis.settings import AnalysisSettings
from timeline.cli.options import number

if TYPE_CHECKING:  # the analysis, devices and limits load when a sound is converted
    from timeline.analysis.staging import Staging

SOUND_SUFFIXES = (".wav", ".flac", ".ogg", ".aif", ".aiff", ".mp3", ".opus", ".caf", ".w64")
OUTPUT_FORMATS = ("haptic", "ahap", "htl")


def _integer(text: str) -> int:
    try:
        return int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a whole number") from None


def _gain(text: str) -> float | None:
    """`auto` (None) or a gain in dB."""
    if text.strip().lower() == "auto":
        return None
    return number(text)


def add_settings_options(p: argparse.ArgumentParser) -> None:
    """One option per analysis setting (--attack, --sensitivity, --no-emphasis, ...)."""
    group = p.add_argument_group("analysis settings (docs/convert.md)")
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
        help="analyse sounds into haptic designs (.haptic, .ahap, or .htl projects)",
        description="Analyse sound files (WAV, FLAC, OGG, AIFF, ...) into amplitude and "
        "frequency envelopes and emphasis. A .htl project also keeps the sound on an audio "
        "track; the design stays editable as envelope breakpoints and emphasis points. Give "
        "several sounds or folders and an output folder to convert a library at once.",
    )
    p.add_argument("sound", nargs="+", help="sound files, or folders of them")
    p.add_argument("-o", "--output", required=True, metavar="OUT",
                   help="a file to write (.haptic, .ahap, .htl) or a folder")  # fmt: skip
    p.add_argument("--format", choices=OUTPUT_FORMATS, default="haptic",
                   help="what to write into an output folder (default: haptic)")  # fmt: skip
    p.add_argument("--jobs", type=_integer, default=0, metavar="N",
                   help="worker processes for many sounds (default: one per core)")  # fmt: skip
    p.add_argument("--gain", type=_gain, default=None, metavar="auto|DB",
                   help="the design's level: auto (default) keeps it within the device's "
                   "limit and raises it when a hand would not feel it clearly; or a gain "
                   "in dB")  # fmt: skip
    p.add_argument(
        "--device",
        default="sim",
        help="device whose limit and hand the level is staged for (default: sim)",
    )
    p.add_argument("--actuator", help="vibration actuator for a vibrotactile device "
                   "(as in check; default: the device's own)")  # fmt: skip
    add_settings_options(p)
    p.set_defaults(func=run)


def staging_for(device: str, actuator: str | None, gain_db: float | None) -> Staging:
    """The level a design should take on the device named (timeline.limits.staging)."""
    from timeline.limits import staging
    from timeline.limits.actuators import actuator as actuator_named
    from timeline.plugins.device_protocol import open_device

    with open_device(device) as d:
        info = d.info
    return staging.staging_for(info, actuator_named(actuator) if actuator else None, gain_db)


def sounds_in(paths: list[str]) -> list[Path]:
    """The sound files named, folders searched (not recursively) for files with sound suffixes."""
    found: list[Path] = []
    for name in paths:
        path = Path(name)
        if path.is_dir():
            found += sorted(p for p in path.iterdir() if p.suffix.lower() in SOUND_SUFFIXES)
        else:
            found.append(path)
    return found


def run(args: argparse.Namespace) -> int:
    from timeline.errors import HapticTimelineError

    settings = settings_from(args)
    sounds = sounds_in(args.sound)
    out = Path(args.output)
    many = len(sounds) != 1 or any(Path(s).is_dir() for s in args.sound) or out.is_dir()
    if many and out.suffix.lower() in tuple(f".{f}" for f in OUTPUT_FORMATS):
        raise HapticTimelineError(f"{len(sounds)} sounds need an output folder, not {out.name}")
    if not sounds:
        raise HapticTimelineError("no sound files found in " + ", ".join(args.sound))
    staging = staging_for(args.device, args.actuator, args.gain)
    if not many:
        from timeline.files.convert import convert_file

        written = convert_file(sounds[0], out, settings, staging)
        for note in written.notes:
            print(f"note: {sounds[0].name}: {note}", file=sys.stderr)
        print(f"converted {sounds[0]} -> {out} ({written.project.duration:.3f} s)",
              file=sys.stderr)  # fmt: skip
        return 0
    out.mkdir(parents=True, exist_ok=True)
    jobs = [(s, out / f"{s.stem}.{args.format}") for s in sounds]
    failed = 0
    bar = Progress(len(jobs)) if sys.stderr.isatty() else None
    from timeline.files.convert import convert_many

    for sound, result in convert_many(jobs, settings, staging, args.jobs or os.cpu_count() or 1):
        if bar is not None:
            bar.step()
        if isinstance(result, str):
            failed += 1
            _say(bar, f"{sound.name}: {result}")
        else:
            for note in result:
                _say(bar, f"note: {sound.name}: {note}")
    if bar is not None:
        bar.close()
    print(f"converted {len(jobs) - failed} of {len(jobs)} sounds -> {out}", file=sys.stderr)
    return 1 if failed else 0


def _say(bar: Progress | None, text: str) -> None:
    if bar is not None:
        bar.clear()
    print(text, file=sys.stderr)
    if bar is not None:
        bar.draw()


class Progress:
    """A one-line progress bar on the terminal's standard error."""

    WIDTH = 30

    def __init__(self, total: int) -> None:
        self.total, self.done = total, 0
        self.draw()

    def step(self) -> None:
        self.done += 1
        self.draw()

    def draw(self) -> None:
        filled = self.WIDTH * self.done // max(self.total, 1)
        bar = "#" * filled + "-" * (self.WIDTH - filled)
        sys.stderr.write(f"\r[{bar}] {self.done}/{self.total}")
        sys.stderr.flush()

    def clear(self) -> None:
        sys.stderr.write("\r" + " " * (self.WIDTH + 24) + "\r")

    def close(self) -> None:
        sys.stderr.write("\n")
        sys.stderr.flush()
