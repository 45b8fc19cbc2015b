"""Where `import` puts a file, in the units the command line speaks.

`--at` and `--length` are seconds on a time project and degrees on a position project. A file in
seconds (a recording, a vibration design) on a position project lies over the knob's angle: one
second becomes one radian (57.3 deg) unless `--length` chooses the span, and a note says which.
"""

from __future__ import annotations

import argparse
from collections.abc import Mapping
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

from timeline.cli.units import amount, on_axis
from timeline.errors import HapticTimelineError
from timeline.model import Fade, Project
from timeline.plugins.file_formats import Imported, Placement, readers_for

# Formats whose files are in seconds whatever the project they go into.
FORMATS_IN_SECONDS = ("audio", "ahap", "haptic")


def in_seconds(path: str) -> bool:
    """True when every format that reads this file's extension reads it in seconds."""
    return all(fmt.name in FORMATS_IN_SECONDS for fmt in readers_for(path))


def _length(p: Placement) -> float:
    """How far a placement reaches past its start, in the file's units."""
    clip = p.clip
    source = clip.get("source_out", p.tile.duration) - clip.get("source_in", 0.0)
    return source * clip.get("stretch", 1.0)


def extent(imported: Imported) -> float:
    """How far the import reaches from its own 0, in the file's units."""
    return max((p.start + _length(p) for p in imported.placements), default=0.0)


def _scaled_clip(clip: Mapping[str, Any], factor: float) -> dict[str, Any]:
    if clip.get("stretch_mode", "squeeze") != "squeeze":
        raise HapticTimelineError(
            "--length cannot stretch a design whose clips repeat their tiles; import it "
            "without --length and stretch it in the editor"
        )
    out = dict(clip, stretch=clip.get("stretch", 1.0) * factor)
    for name in ("fade_in", "fade_out"):
        fade = clip.get(name)
        if isinstance(fade, Fade):
            out[name] = replace(fade, length=fade.length * factor)
    return out


def stretched(imported: Imported, factor: float) -> Imported:
    """The import `factor` times as long: starts, clips and fades scaled."""
    placements = tuple(
        replace(p, start=p.start * factor, clip=_scaled_clip(p.clip, factor))
        for p in imported.placements
    )
    return replace(imported, placements=placements)


@dataclass
class Arrangement:
    """`import`'s arrange step (timeline.files.importing.Arrange): --at and --length in the
    project's units; `at` and `axis` say where the import went."""

    args: argparse.Namespace
    at: float = 0.0
    axis: str = "time"
    length: float | None = None

    def start(self, project: Project) -> float:
        """--at in axis units (0 when not given); --length read too, both before the file."""
        self.axis = project.axis
        self.at = 0.0 if self.args.at is None else on_axis(self.args.at, self.axis, "--at")
        if self.args.length is not None:
            self.length = on_axis(self.args.length, self.axis, "--length")
        return self.at

    def placements(self, project: Project, imported: Imported) -> Imported:
        """The import stretched to --length, with a note when seconds became an angle."""
        axis = project.axis
        name = Path(self.args.file).name
        reach = extent(imported)
        target = reach  # one file unit per axis unit: a second becomes a radian
        if self.length is not None:
            target = self.length
            if not reach > 0:
                raise HapticTimelineError(f"{name} has no length to stretch to --length")
            imported = stretched(imported, target / reach)
        if axis != "position" or not reach > 0 or not in_seconds(self.args.file):
            return imported
        became = f"its {reach:.6g} s {amount(target, axis)} of the knob's angle"
        if self.length is None:
            note = (f"{name} is in seconds: one radian per second made {became} (1 s = "
                    f"{amount(1.0, axis)}); --length DEG gives it another span")  # fmt: skip
        else:
            per_second = amount(target / reach, axis)
            note = f"{name} is in seconds: --length made {became} (1 s = {per_second})"
        return replace(imported, notes=(*imported.notes, note))


def check_project_path(text: str) -> None:
    """Refuse an --into that is not a .htl file in an existing folder, before reading."""
    from timeline.files.atomic import check_target

    path = Path(text)
    if path.suffix.lower() != ".htl":
        raise HapticTimelineError(
            f"--into names the project file, which ends in .htl: {path.name} does not"
        )
    if not path.exists():
        check_target(path)
