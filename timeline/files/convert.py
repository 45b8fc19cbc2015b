"""`convert`: a sound file to a haptic design kept as editable data, and the sound beside it.

The analysis (timeline.analysis) gives amplitude and frequency envelopes and emphasis; they are
placed on a drive track as a vibration design (timeline.edits.vibration: envelope breakpoints and
emphasis kept as data the designer edits on the timeline). In a project the sound itself goes on
an `audio` context track at the same time, to see and hear while editing; .haptic and .ahap
files hold the design only.
"""

from __future__ import annotations

import os
import re
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from timeline import edits
from timeline.analysis import DEFAULTS, AnalysisSettings, SoundAnalysis
from timeline.analysis.source import analyse_file, mono_samples
from timeline.analysis.staging import Staging, stage
from timeline.edits.sound_track import add_sound
from timeline.edits.vibration import (
    Emphasis,
    VibrationDesign,
    emphasis_of,
    place_design,
    place_design_clip,
)
from timeline.errors import ConvertError, HapticTimelineError
from timeline.model import Project

MAX_SOUND_SECONDS = 3600.0  # a project keeps the source sound up to an hour long
PROJECT_EXTENSIONS = (".htl",)
# libsndfile's note of a chunk whose declared size runs past the end of the file, e.g.
# "data : 40000 (should be 19979)": the file is truncated (as `import` judges it).
_SHORT_CHUNK = re.compile(
    r"^\s*(data|SSND|Riff size|RIFF|FORM)\s*:\s*(\d+)\s*\(should be (\d+)\)", re.MULTILINE
)


@dataclass(frozen=True)
class ConvertedSound:
    """A sound file's analysis, and its mono samples when the project is to keep them."""

    path: Path
    analysis: SoundAnalysis
    sound: np.ndarray | None
    gain_db: float = 0.0  # the gain staging applied to the design (timeline.analysis.staging)
    notes: tuple[str, ...] = ()  # what staging did or left for the user to decide


def _check_complete(path: Path) -> None:
    """ConvertError if the sound file's header promises more audio than it holds (what
    `import` refuses; convert analysed the part there was)."""
    import soundfile

    try:
        with soundfile.SoundFile(path) as f:
            info = f.extra_info
    except (soundfile.LibsndfileError, RuntimeError, TypeError, ValueError):
        return  # not readable at all: the analysis says so in its own sentence
    for match in _SHORT_CHUNK.finditer(info):
        if int(match.group(3)) < int(match.group(2)):
            raise ConvertError(
                f"{path.name} is truncated: its header promises more audio than the file holds"
            )


def design_of_analysis(analysis: SoundAnalysis) -> VibrationDesign:
    """The analysis as a vibration design (breakpoints in seconds, values 0..1)."""
    return VibrationDesign(
        amplitude=analysis.amplitude,  # (n, 2) arrays: held as arrays, no object per point
        frequency=analysis.frequency,
        emphasis=tuple(Emphasis(float(t), float(a), float(f)) for t, a, f in analysis.emphasis),
        duration=float(analysis.duration),
    )


def analyse_sound_file(
    path: str | os.PathLike,
    settings: AnalysisSettings = DEFAULTS,
    *,
    keep_sound: bool = True,
    progress: Callable[[float], None] | None = None,
    staging: Staging | None = None,
) -> ConvertedSound:
    """Analyse a sound file; with `keep_sound` also read it (mono) for an audio track.

    `progress` hears the fraction analysed; it may raise to stop (the editor's Cancel).
    `staging` sets the design's level for a device (none: the sound's own level).
    """
    path = Path(path)
    _check_complete(path)
    import soundfile

    try:
        analysis = analyse_file(path, settings, progress)
    except soundfile.LibsndfileError as exc:  # a damaged stream found while decoding
        reason = str(exc.error_string).rstrip(".")
        raise ConvertError(f"{path.name} could not be read to the end ({reason})") from None
    gain_db, notes = 0.0, ()
    if staging is not None:
        staged = stage(analysis, staging)
        analysis, gain_db, notes = staged.analysis, staged.gain_db, staged.notes
    if not keep_sound:
        return ConvertedSound(path, analysis, None, gain_db, notes)
    if analysis.duration > MAX_SOUND_SECONDS:
        raise ConvertError(
            f"{path.name} lasts {analysis.duration / 60:.0f} minutes; a project keeps sounds up to "
            f"{MAX_SOUND_SECONDS / 60:.0f} minutes (convert it to .haptic or .ahap instead)"
        )
    return ConvertedSound(path, analysis, mono_samples(path), gain_db, notes)


def place_converted(
    project: Project, converted: ConvertedSound, *, at: float = 0.0, drive_track: str | None = None
) -> Project:
    """The design on a drive track (the first, or `drive_track`) and the sound on a new audio
    track, both starting at `at` seconds."""
    path, analysis = converted.path, converted.analysis
    if converted.sound is not None:
        project, _ = add_sound(
            project, converted.sound, analysis.rate, name=path.stem, source=path.name, at=at
        )
    design = design_of_analysis(analysis)
    return place_design(
        project, design, at=at, track_id=drive_track, name=path.stem, source=path.name
    )


def reanalysed(project: Project, clip_id: str, analysis: SoundAnalysis) -> tuple[Project, str]:
    """A converted design's clip and its emphasis replaced by a new analysis of the same sound,
    at the clip's start, on its track, with its gain; every other clip is left as it was.
    Returns the project and the new design clip's id."""
    track, clip = project.find_clip(clip_id)
    tile = project.tile(clip.tile_id)
    name, source = getattr(tile, "name", "vibration"), getattr(tile, "source", "")
    project = edits.remove_clips(project, [clip_id, *emphasis_of(project, clip_id)])
    project, new = place_design_clip(
        project, design_of_analysis(analysis), at=clip.start, track_id=track.id, name=name,
        source=source,
    )  # fmt: skip
    if clip.gain != 1.0:
        project = edits.set_clip(project, new, gain=clip.gain)
    return project, new


def sound_to_project(
    path: str | os.PathLike,
    settings: AnalysisSettings = DEFAULTS,
    *,
    project: Project | None = None,
    at: float = 0.0,
    keep_sound: bool = True,
    drive_track: str | None = None,
    staging: Staging | None = None,
) -> Project:
    """A project (new, or `project` extended) with the sound's design, and the sound itself."""
    converted = analyse_sound_file(path, settings, keep_sound=keep_sound, staging=staging)
    base = edits.new_project() if project is None else project
    return place_converted(base, converted, at=at, drive_track=drive_track)


@dataclass(frozen=True)
class Written:
    """What `convert_file` wrote: the project it made, the staging gain (dB) and its notes."""

    project: Project
    gain_db: float
    notes: tuple[str, ...]


def convert_file(
    sound: str | os.PathLike,
    output: str | os.PathLike,
    settings: AnalysisSettings = DEFAULTS,
    staging: Staging | None = None,
    *,
    stages: Callable[[str], None] | None = None,
) -> Written:
    """Analyse `sound` and write the design to `output` (.haptic, .ahap or a .htl project).

    `stages` hears "analysed", "placed" and "written" as each step ends (the memory bench).
    """
    from timeline.files import projectfile
    from timeline.files.exporting import export_project

    ended = stages or (lambda stage: None)
    output = Path(output)
    keep = output.suffix.lower() in PROJECT_EXTENSIONS
    converted = analyse_sound_file(sound, settings, keep_sound=keep, staging=staging)
    ended("analysed")
    project = place_converted(edits.new_project(), converted)
    ended("placed")
    if keep:
        projectfile.save(project, output)
    else:
        export_project(project, output)
    ended("written")
    return Written(project, converted.gain_db, converted.notes)


def convert_one(
    sound: Path, output: Path, settings: AnalysisSettings, staging: Staging | None
) -> tuple[str, ...] | str:
    """Convert one sound (a worker's job): its staging notes, or the sentence saying why not."""
    try:
        return convert_file(sound, output, settings, staging).notes
    except (HapticTimelineError, OSError) as exc:
        return str(exc)


def convert_many(
    jobs: list[tuple[Path, Path]],
    settings: AnalysisSettings,
    staging: Staging | None,
    workers: int,
) -> Iterator[tuple[Path, tuple[str, ...] | str]]:
    """Convert (sound, output) pairs over `workers` processes (one: in this one), each result
    as it finishes: its notes, or why it failed."""
    if workers <= 1 or len(jobs) == 1:
        for sound, output in jobs:
            yield sound, convert_one(sound, output, settings, staging)
        return
    from concurrent.futures import ProcessPoolExecutor, as_completed

    with ProcessPoolExecutor(max_workers=min(workers, len(jobs))) as pool:
        futures = {pool.submit(convert_one, s, o, settings, staging): s for s, o in jobs}
        for future in as_completed(futures):
            yield futures[future], future.result()
