"""Export a project (or one tile) to a file, choosing the writer by the file's extension.

Shared by the CLI (`haptic-timeline export`) and the GUI. Files are written to a temporary name
beside the target and renamed into place, so a failed export never leaves a partial file.

An optional `progress(fraction)` hears how far an export is: rendering (the slow part) reports
after every chunk, up to RENDER_SHARE; writing the file is one last step to 1.0. A progress
callback that raises stops the export, and nothing is left behind.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import numpy as np

from timeline.errors import FormatError, HapticTimelineError
from timeline.files.atomic import check_target, write_atomically
from timeline.model import Project
from timeline.plugins.file_formats import Layers, Progress, writer_for
from timeline.rendering import mixer
from timeline.signal import memory
from timeline.tiles import SampledTile, Tile

RENDER_SHARE = 0.9  # the part of an export's progress that rendering reports
CHUNKS = 50  # a render is reported in about this many pieces ...
MIN_CHUNK_SAMPLES = 2**16  # ... of at least this many samples each


def project_layers(
    project: Project,
    rate: float | None = None,
    quality: str = "normal",
    progress: Progress | None = None,
) -> Layers:
    """The project's mixed layers from 0 to its end, at `rate` (default: the project's rate).

    Rendered in chunks; `progress` hears the fraction rendered after each one.
    """
    if project.duration <= 0:
        raise FormatError("the project has no clips to export")
    rate = float(rate or project.rate)
    total = mixer.grid_length(0.0, project.duration, rate)
    memory.require(
        2 * 8 * total * len(mixer.active_tracks(project)),
        f"exporting {memory.count_text(total)} samples per layer",
        "export at a lower rate",
    )
    chunk = max(project.duration / CHUNKS, MIN_CHUNK_SAMPLES / rate)
    parts: dict[str, list[np.ndarray]] = {}
    done = 0
    pieces = mixer.render_chunks(project, 0.0, project.duration, rate, quality, chunk=chunk)
    for _, layers in pieces:
        for kind_id, values in layers.items():
            parts.setdefault(kind_id, []).append(values)
        done += max((len(v) for v in layers.values()), default=0)
        if progress:
            progress(min(1.0, done / total))
    if not parts:
        raise FormatError("every track with clips is muted, so there is nothing to export")
    columns = {kind_id: np.concatenate(values) for kind_id, values in parts.items()}
    return Layers(columns, rate, 0.0, project.axis)


def _scaled(progress: Progress | None, share: float) -> Progress | None:
    """A progress callback that maps 0..1 onto 0..share of `progress`."""
    return None if progress is None else (lambda fraction: progress(fraction * share))


def tile_layers(tile: Tile, rate: float | None = None, name: str = "value") -> Layers:
    """One tile as a single column: a sampled tile's own samples, other tiles rendered at `rate`."""
    if isinstance(tile, SampledTile) and rate in (None, tile.rate):
        return Layers({name: tile.data.astype(np.float64, copy=False)}, tile.rate)
    if rate is None:
        raise FormatError(f"tile {tile.name!r} is not sampled: give a rate to export it")
    from timeline.signal.render_presets import preset

    n = max(1, round(tile.duration * rate))
    return Layers({name: tile.render(0.0, 1.0 / rate, n, preset("exact"))}, float(rate))


def export_project(
    project: Project,
    path: str | os.PathLike,
    *,
    rate: float | None = None,
    progress: Progress | None = None,
    **options: Any,
) -> str | None:
    """Write a project to a file whose extension picks the format (.wav, .csv, .mat, .ahap, ...).

    Returns what the writer says about the file, if anything (a firmware table's size)."""
    path = Path(path)
    fmt = writer_for(path)
    if fmt.writes == "layers":
        layers = project_layers(project, rate, progress=_scaled(progress, RENDER_SHARE))
        write_layers(layers, path, progress=progress, **options)
        return None
    if project.duration <= 0:
        raise FormatError("the project has no clips to export")
    if rate is not None:
        options["rate"] = rate
    if progress:
        progress(0.0)
    said = _write(fmt, project, path, options)
    if progress:
        progress(1.0)
    return said


def write_layers(
    layers: Layers, path: str | os.PathLike, *, progress: Progress | None = None, **options: Any
) -> None:
    """Write rendered layers to a table or audio file chosen by its extension (.csv, .wav, ...).

    `progress` hears 1.0 once the file is in place.
    """
    path = Path(path)
    fmt = writer_for(path)
    if fmt.writes != "layers":
        raise FormatError(f"rendered layers cannot be written as {fmt.name}; use export")
    _write(fmt, layers, path, options)
    if progress:
        progress(1.0)


def export_tile(
    tile: Tile, path: str | os.PathLike, *, rate: float | None = None, **options: Any
) -> None:
    """Write one tile as a single column (.csv, .txt, .mat, .wav): the palette's save-as."""
    path = Path(path)
    fmt = writer_for(path)
    if fmt.writes != "layers":
        raise FormatError(f"a single tile cannot be written as {fmt.name}; export a project")
    _write(fmt, tile_layers(tile, rate, name=options.pop("name", "value")), path, options)


def _write(fmt: Any, source: Any, path: Path, options: dict[str, Any]) -> str | None:
    """Write atomically; the writer is told the final path as `target` (it writes to a temporary
    beside it), so names inside the file and media written beside it follow the real name.
    Returns the writer's one line about the file, when it says one."""
    said: list[Any] = []
    try:
        check_target(path)
        write_atomically(
            path, lambda tmp: said.append(fmt.write(source, tmp, target=path, **options))
        )
        return said[0] if said and isinstance(said[0], str) else None
    except HapticTimelineError:
        raise
    except OSError as exc:
        raise FormatError(f"cannot write {path} ({exc.strerror or exc})") from None


def export_project_file(
    project_path: str | os.PathLike, path: str | os.PathLike, **kwargs: Any
) -> None:
    """Load a project file and export it (see export_project)."""
    from timeline.files import projectfile

    export_project(projectfile.load(project_path), path, **kwargs)
