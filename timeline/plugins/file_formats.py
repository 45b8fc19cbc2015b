"""The file-format plugin protocol: what a reader returns and what a writer is given.

A format plugin is an object registered under the `haptic_timeline.importers` entry point. It
declares its name, file extensions, what it reads (a tile, or a whole design of clips per track
kind) and what it writes (the rendered layers, or the project itself). A reader returns None to
decline a file it does not recognise, so the next format with that extension is tried; a file it
recognises but cannot read raises FormatError with one sentence.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from types import MappingProxyType
from typing import Any, Literal, Protocol, runtime_checkable

import numpy as np

from timeline import plugins
from timeline.errors import FormatError
from timeline.tiles import Tile

Progress = Callable[[float], None]  # called with the fraction done, 0.0 .. 1.0


@dataclass(frozen=True)
class Placement:
    """A tile placed by a reader: where it starts and on what kind of track.

    `kind` None means the track kind the user chose; placements that share a `track` name go on
    one track; `clip` holds further timeline.model.Clip fields (gain, source_in, fades, ...).
    """

    tile: Tile
    start: float = 0.0
    kind: str | None = None
    track: str = ""
    clip: Mapping[str, Any] = field(default_factory=lambda: MappingProxyType({}))


@dataclass(frozen=True)
class TrackInfo:
    """Settings of a track in an imported design; `key` is the placements' `track`."""

    key: str
    name: str
    kind: str
    gain: float = 1.0
    mute: bool = False
    solo: bool = False


@dataclass(frozen=True)
class Imported:
    """What a reader returns: tiles placed as clips, and the tracks of a design if it has any."""

    placements: tuple[Placement, ...]
    tracks: tuple[TrackInfo, ...] = ()
    notes: tuple[str, ...] = ()  # what was approximated or dropped, for the message bar
    markers: tuple[tuple[str, float], ...] = ()  # (name, position after the import's start)


@dataclass(frozen=True)
class Layers:
    """Rendered layers (or one tile) to write: named float64 columns sampled at `rate`."""

    columns: Mapping[str, np.ndarray]
    rate: float
    start: float = 0.0
    axis: str = "time"

    @property
    def length(self) -> int:
        return max((len(v) for v in self.columns.values()), default=0)


@runtime_checkable
class Format(Protocol):
    """A file format plugin."""

    name: str
    extensions: tuple[str, ...]  # lower case, with the dot: (".wav", ".flac")
    reads: Literal["tile", "design", ""]
    writes: Literal["layers", "project", ""]
    options: tuple[str, ...]  # read options it understands: "channel", "column", "rate"

    def read(
        self, path: Path, *, progress: Progress | None = None, **options: Any
    ) -> Tile | Imported | None:
        """Read a file: a tile, placed tiles, or None to decline a file it does not recognise."""
        ...

    def write(self, source: Any, path: Path, **options: Any) -> None:
        """Write Layers (writes == "layers") or a Project (writes == "project") to path."""
        ...


def all_formats() -> dict[str, Format]:
    """Every registered format plugin by name."""
    return dict(plugins.load_group(plugins.IMPORTERS))


def extension(path: str | os.PathLike) -> str:
    """A path's extension in lower case with its dot ("" when it has none)."""
    return Path(path).suffix.lower()


def readers_for(path: str | os.PathLike) -> list[Format]:
    """The formats that read files with this path's extension (FormatError if none)."""
    ext = extension(path)
    found = [f for f in all_formats().values() if f.reads and ext in f.extensions]
    if not found:
        known = sorted({e for f in all_formats().values() if f.reads for e in f.extensions})
        raise FormatError(
            f"no format reads {ext or 'extension-less'} files (known: {', '.join(known)})"
        )
    return found


def writer_for(path: str | os.PathLike) -> Format:
    """The format that writes files with this path's extension (FormatError if none).

    The plugin named after the extension ("csv" for .csv) is tried first, then the rest in name
    order; the search stops loading plugins at the first that fits.
    """
    ext = extension(path)
    for _, f in plugins.iter_group(plugins.IMPORTERS, first=ext.lstrip(".")):
        if f.writes and ext in f.extensions:
            return f
    known = sorted({e for f in all_formats().values() if f.writes for e in f.extensions})
    raise FormatError(
        f"no format writes {ext or 'extension-less'} files (known: {', '.join(known)})"
    )


def as_imported(result: Tile | Imported) -> Imported:
    """A reader's result as placements (a bare tile is one placement at 0 on the chosen kind)."""
    return result if isinstance(result, Imported) else Imported((Placement(result),))
