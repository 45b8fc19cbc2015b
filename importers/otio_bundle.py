"""OTIO bundles (.otioz): the timeline and every medium it names in one zip, OTIO's own layout.

The layout is the one OTIO's otioz adapter writes and reads: `version.txt` ("1.0.0"),
`content.otio` (the timeline, deflated) and `media/` (the files, stored), every reference's
`target_url` being `media/NAME`. OTIO's own bundler moves only each clip's active medium; ours
carries every reference (the .haptic beside each WAV too). Unzipped, the same files are an
.otiod folder. Reading opens `content.otio` and unpacks `media/` into a temporary folder for as
long as the reader needs it.
"""

from __future__ import annotations

import contextlib
import tempfile
import zipfile
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import opentimelineio as otio

from timeline.plugins.file_formats import FormatError

VERSION = "1.0.0"
CONTENT = "content.otio"
MEDIA = "media"
MAX_UNPACKED = 4 << 30  # bytes of media a bundle may unpack to


class MediaStore:
    """Where an export's media go, and how its references name them."""

    def __init__(self, folder: Path, prefix: str = "") -> None:
        self.folder = folder
        self.prefix = prefix
        self.files: list[Path] = []

    @classmethod
    @contextlib.contextmanager
    def bundled(cls) -> Iterator[MediaStore]:
        """A store in a temporary folder, named `media/NAME` as inside a bundle."""
        with tempfile.TemporaryDirectory(prefix="otioz-") as folder:
            yield cls(Path(folder), MEDIA + "/")

    def path(self, name: str) -> Path:
        path = self.folder / name
        self.files.append(path)
        return path

    def url(self, path: Path) -> str:
        """The file's target_url: its name beside the .otio, or `media/NAME` in a bundle."""
        return self.prefix + path.name


def write_bundle(timeline: otio.schema.Timeline, store: MediaStore, path: Path) -> None:
    """Zip the timeline and the store's files as an .otioz at path."""
    content = otio.adapters.write_to_string(timeline, adapter_name="otio_json")
    with zipfile.ZipFile(path, "w") as bundle:
        bundle.writestr("version.txt", VERSION, compress_type=zipfile.ZIP_DEFLATED)
        bundle.writestr(CONTENT, content, compress_type=zipfile.ZIP_DEFLATED)
        for file in store.files:
            bundle.write(file, f"{MEDIA}/{file.name}", compress_type=zipfile.ZIP_STORED)


@contextlib.contextmanager
def opened(
    path: Path, wants_media: Callable[[otio.schema.Timeline], bool]
) -> Iterator[tuple[otio.schema.Timeline, Path]]:
    """An .otio's timeline and the folder its relative media resolve against; for an .otioz,
    its content and a temporary folder holding its unpacked media when `wants_media(timeline)`."""
    if path.suffix.lower() != ".otioz":
        yield (
            _parsed(path, lambda: otio.adapters.read_from_file(str(path), "otio_json")),
            (path.parent),
        )
        return
    try:
        bundle = zipfile.ZipFile(path)
    except (zipfile.BadZipFile, OSError) as exc:
        raise FormatError(f"{path.name} is not an OTIO bundle (a zip file): {exc}") from None
    with bundle, tempfile.TemporaryDirectory(prefix="otioz-") as folder:
        try:
            text = bundle.read(CONTENT).decode("utf-8")
        except KeyError:
            raise FormatError(f"{path.name} holds no {CONTENT}: not an OTIO bundle") from None
        except (zipfile.BadZipFile, UnicodeDecodeError, OSError) as exc:
            raise FormatError(f"{path.name}'s {CONTENT} cannot be read ({exc})") from None
        timeline = _parsed(path, lambda: otio.adapters.read_from_string(text, "otio_json"))
        wanted = wants_media(timeline)
        media = [i for i in bundle.infolist() if wanted and i.filename.startswith(MEDIA + "/")]
        if sum(i.file_size for i in media) > MAX_UNPACKED:
            raise FormatError(
                f"{path.name}'s media unpack to more than {MAX_UNPACKED >> 30} GiB; unzip it "
                "and import its content.otio instead"
            )
        try:
            for info in media:
                bundle.extract(info, folder)  # zipfile keeps every name inside the folder
        except (zipfile.BadZipFile, OSError) as exc:
            raise FormatError(f"{path.name}'s media cannot be unpacked ({exc})") from None
        yield timeline, Path(folder)


def _parsed(path: Path, parse) -> otio.schema.Timeline:
    try:
        timeline = parse()
    except Exception as exc:  # OTIO's parser raises many types on malformed input
        detail = str(exc).splitlines()[0][:120] if str(exc) else type(exc).__name__
        raise FormatError(f"{path.name} is not a readable OTIO file ({detail})") from None
    found = _timeline_in(timeline)
    if found is None:
        raise FormatError(f"{path.name} holds no OTIO timeline")
    return found


def _timeline_in(root: Any) -> otio.schema.Timeline | None:
    """The timeline a file holds: itself, the first in a collection, or a bare stack or track
    as a timeline of its own (as OTIO's tools save a part of an edit)."""
    if isinstance(root, otio.schema.Timeline):
        return root
    if isinstance(root, otio.schema.SerializableCollection):
        for child in root:
            found = _timeline_in(child)
            if found is not None:
                return found
        return None
    if isinstance(root, otio.schema.Stack):
        timeline = otio.schema.Timeline(root.name)
        timeline.tracks = root
        return timeline
    if isinstance(root, otio.schema.Track):
        timeline = otio.schema.Timeline(root.name)
        timeline.tracks.append(root)
        return timeline
    return None
