"""Import a file into a project: find the format, read it, place its tiles as clips.

Shared by the CLI (`haptic-timeline import`) and the GUI. Every function here is pure with respect
to the project: a failure raises one HapticTimelineError and leaves no partial change behind.
"""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import Any, Protocol

import numpy as np

from timeline import edits
from timeline.edits import markers as marker_edits
from timeline.errors import EditError, FormatError, HapticTimelineError
from timeline.files import gc_pause
from timeline.model import Clip, Project
from timeline.model.markers import Marker
from timeline.plugins.file_formats import (
    Imported,
    Progress,
    TrackInfo,
    as_imported,
    readers_for,
)
from timeline.plugins.track_kinds import DEFAULT_KIND, track_kind
from timeline.tiles import GeneratorTile, SplineTile, Tile

_PROBE_SAMPLES = 64  # samples of each new tile rendered to prove it renders (check_placed)


class Arrange(Protocol):
    """Where an import into a project file starts and what it places, decided by the caller
    (the command line's units: degrees on a position project, and --length)."""

    def start(self, project: Project) -> float:
        """Where the import starts, in axis units (asked before the file is read)."""
        ...

    def placements(self, project: Project, imported: Imported) -> Imported:
        """What to place of what the file held."""
        ...


def check_readable(path: Path) -> None:
    """Raise FormatError unless path is an existing, non-empty regular file."""
    if not path.exists():
        raise FormatError(f"{path} does not exist")
    if path.is_dir():
        raise FormatError(f"{path} is a directory, not a file")
    if path.stat().st_size == 0:
        raise FormatError(f"{path.name} is empty (zero bytes)")


def read_file(
    path: str | os.PathLike, *, progress: Progress | None = None, **options: Any
) -> Imported:
    """Read a file with the first format for its extension that recognises it.

    Options left as None are dropped; an option the format does not take is refused.
    """
    path = Path(path)
    check_readable(path)
    given = {k: v for k, v in options.items() if v is not None}
    for fmt in readers_for(path):
        unused = sorted(set(given) - set(fmt.options))
        if unused:
            raise FormatError(f"the {unused[0]} option does not apply to {fmt.name} files")
        try:
            with gc_pause.paused():  # a JSON design is millions of containers, none garbage
                result = fmt.read(path, progress=progress, **given)
        except FormatError:
            raise
        except HapticTimelineError as exc:
            raise FormatError(f"{path.name} cannot be imported: {exc}") from None
        except OSError as exc:
            raise FormatError(f"cannot read {path.name} ({exc.strerror or exc})") from None
        if result is not None:
            return as_imported(result)
    raise FormatError(f"{path.name} is not a file any {path.suffix.lower()} format recognises")


def import_file(
    project: Project,
    path: str | os.PathLike,
    *,
    kind: str | None = None,
    at: float = 0.0,
    gain: float = 1.0,
    progress: Progress | None = None,
    **options: Any,
) -> tuple[Project, list[str]]:
    """Import a file into a project at time `at`; returns the new project and the new clip ids.

    A tile goes on the first track of `kind` (default drive), created if needed; a design's clips
    go on tracks of their own kinds: the file's n-th track of a kind on the project's n-th.
    """
    _check_start(project, at)  # before the (maybe long) read
    imported = read_file(path, progress=progress, **options)
    return _usable(place, project, imported, Path(path).name, kind=kind or DEFAULT_KIND, at=at,
                   gain=gain)  # fmt: skip


def place(
    project: Project,
    imported: Imported,
    *,
    kind: str = DEFAULT_KIND,
    at: float = 0.0,
    gain: float = 1.0,
    track_id: str | None = None,
) -> tuple[Project, list[str]]:
    """Add an import's tiles to the palette and its placements as clips (see import_file).

    With `track_id`, placements that name no kind or track of their own (a recording, a table)
    go on that track, and its kind gives them meaning.
    """
    _check_start(project, at)
    if track_id is not None:
        kind = project.track(track_id).kind
    infos = {t.key: t for t in imported.tracks}
    targets: dict[tuple[str, str], str] = {}  # (kind, source track name) -> project track id
    tile_ids: dict[int, str] = {}  # id(tile) -> project tile id: a tile placed twice is added once
    clip_ids: list[str] = []
    batch: list = []  # clips placed in one pass (edits.add_clips) until a track is added
    for placement in imported.placements:
        if track_id is not None and placement.kind is None and not placement.track:
            target = track_id
        else:
            key = (placement.kind or kind, placement.track)
            if key not in targets:  # may add a track: place what came before it first
                project = _place_batch(project, batch, tile_ids, clip_ids)
                batch = []
            project, target = _target_track(project, key[0], placement.track, targets, infos)
        fields = dict(placement.clip)
        fields["gain"] = gain * fields.get("gain", 1.0)
        tile = tile_ids.get(id(placement.tile), placement.tile)
        batch.append((target, tile, at + placement.start, fields))
    project = _place_batch(project, batch, tile_ids, clip_ids)
    if imported.markers:
        moved = tuple(Marker(name, at + position) for name, position in imported.markers)
        project = marker_edits.add_markers(project, moved)
    return project, clip_ids


def _place_batch(
    project: Project, batch: list, tile_ids: dict[int, str], clip_ids: list[str]
) -> Project:
    """Place a batch of clips; note the ids its new tiles and clips got."""
    project, placed = edits.add_clips(project, batch)
    for (_, tile, _, _), clip_id in zip(batch, placed, strict=True):
        if not isinstance(tile, str):
            tile_ids[id(tile)] = project.find_clip(clip_id)[1].tile_id
    clip_ids += placed
    return project


def place_checked(
    project: Project, imported: Imported, name: str, **where: Any
) -> tuple[Project, list[str]]:
    """place(project, imported, **where), refused with one sentence naming the file `name` unless
    every verb can use the result (check_placed): the editor's import."""
    return _usable(place, project, imported, name, **where)


def _usable(
    placer: Any, project: Project, imported: Imported, name: str, **where: Any
) -> tuple[Project, list[str]]:
    """placer(project, imported, **where), refused with one sentence naming the file unless every
    verb can use the result (importing.check_placed)."""
    placed, clip_ids = placer(project, imported, **where)
    try:
        check_placed(placed, clip_ids)
    except EditError as exc:
        raise FormatError(f"{name} cannot be imported: {exc}") from None
    return placed, clip_ids


def check_placed(project: Project, clip_ids: list[str]) -> None:
    """Raise EditError unless the new clips are ones every verb can use: none starts before the
    timeline's 0, the project stays short enough for one render at its rate (MAX_SAMPLES), and
    each new closed-form tile (generator or spline; one per distinct shape) renders its first
    samples as finite numbers: a guard against a shape its constructor let through but a
    renderer cannot draw. Samples are finite by construction, and an emphasis is a bounded
    pulse, so those are not probed (a .haptic file has one per emphasis)."""
    from timeline.rendering.mixer import MAX_SAMPLES

    probes: dict[str, tuple[Tile, Clip]] = {}
    for clip_id in clip_ids:
        clip = project.find_clip(clip_id)[1]
        if project.axis == "time" and clip.start < 0:
            raise EditError(f"a clip would start at {clip.start:g} s, before the timeline's 0")
        tile = project.tile(clip.tile_id)
        _check_text(tile.name)
        if isinstance(tile, SplineTile) or (
            isinstance(tile, GeneratorTile) and tile.generator != "emphasis"
        ):
            probes.setdefault(tile.key, (tile, clip))
    for track in project.tracks:
        _check_text(track.name)
    if project.duration * project.rate > MAX_SAMPLES:
        raise EditError(
            f"the project would last {project.duration:.6g} {project.unit}, longer than one "
            f"render holds at {project.rate:g} per {project.unit} "
            f"({MAX_SAMPLES / project.rate:.6g} {project.unit})"
        )
    for tile, clip in probes.values():
        _probe(tile, clip, project.rate)


def _check_text(name: str) -> None:
    """EditError for a name holding a lone surrogate (no character: neither printed nor saved)."""
    if not name.isascii():
        try:
            name.encode("utf-8")
        except UnicodeEncodeError:
            raise EditError(
                f"the name {name!r} is not valid text (it holds a lone surrogate)"
            ) from None


def _probe(tile: Tile, clip: Clip, rate: float) -> None:
    """Render a clip's first samples of its tile (draft); EditError unless finite."""
    from timeline.signal.render_presets import preset

    n = max(1, min(_PROBE_SAMPLES, int(clip.duration * rate)))
    try:
        values = tile.render(clip.source_in, 1.0 / (rate * clip.stretch), n, preset("draft"))
    except (ArithmeticError, ValueError, MemoryError) as exc:
        raise EditError(f"tile {tile.name!r} cannot be rendered ({exc})") from None
    if not np.all(np.isfinite(values)):
        raise EditError(f"tile {tile.name!r} renders values that are not finite numbers")


def _check_start(project: Project, at: float) -> None:
    """Refuse a start the import would never play from (before 0 s on the time axis)."""
    if not math.isfinite(at) or (project.axis == "time" and at < 0):
        raise EditError(
            f"an import cannot start at {at:g} {project.unit}: the timeline starts at 0"
        )


def _target_track(
    project: Project,
    kind: str,
    source_track: str,
    targets: dict[tuple[str, str], str],
    infos: dict[str, TrackInfo],
) -> tuple[Project, str]:
    """The project track for a source track: the n-th of its kind, created when missing."""
    key = (kind, source_track)
    if key in targets:
        return project, targets[key]
    track_kind(kind)  # an unknown kind fails here with the choices named
    used = sum(1 for k, _ in targets if k == kind)
    existing = [t.id for t in project.tracks if t.kind == kind]
    if used < len(existing):
        targets[key] = existing[used]
        return project, targets[key]
    info = infos.get(source_track)
    if info is None:
        project, track_id = edits.add_track(project, kind)
    else:
        project, track_id = edits.add_track(
            project, kind, info.name, gain=info.gain, mute=info.mute, solo=info.solo
        )
    targets[key] = track_id
    return project, track_id


def import_into_project_file(
    path: str | os.PathLike,
    project_path: str | os.PathLike,
    *,
    kind: str | None = None,
    at: float = 0.0,
    gain: float = 1.0,
    progress: Progress | None = None,
    arrange: Arrange | None = None,
    **options: Any,
) -> tuple[list[str], tuple[str, ...]]:
    """Import into a project file (created on the time axis at 10 kHz if missing), atomically.

    Returns the new clip ids and the reader's notes (what it assumed, clamped or skipped). On any
    error the project file is left exactly as it was. `arrange`, when given, decides where the
    import starts instead of `at` and what it places.
    """
    from timeline.files import projectfile

    project_path = Path(project_path)
    project = projectfile.load(project_path) if project_path.exists() else edits.new_project()
    if arrange is not None:
        at = arrange.start(project)
    _check_start(project, at)  # before the (maybe long) read
    imported = read_file(path, progress=progress, **options)
    if arrange is not None:
        imported = arrange.placements(project, imported)
    project, clip_ids = _usable(place, project, imported, Path(path).name,
                                kind=kind or DEFAULT_KIND, at=at, gain=gain)  # fmt: skip
    projectfile.save(project, project_path)
    return clip_ids, imported.notes
