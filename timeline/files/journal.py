"""An editing session's autosave as a journal: a record per edit, a full snapshot now and then.

A session keeps a folder of its own:

- `meta.json`: the writing process's id and the project file the session edits;
- `journal-G.log`: generation G's records, appended one per project-changing edit (an undo and a
  redo too), each `<u64 length><u32 CRC-32>` then its payload (`<u32 n>`, n bytes of JSON, then
  any raw samples), written with one unbuffered write to the operating system the moment it is
  made: a killed process cannot lose a record whose write returned. Nothing is synced, so a power
  cut loses what the system had not yet written back (Linux: up to about 30 s);
- `snapshot-G.htl`: the project file of the state generation G starts from, written atomically
  (and synced) on a thread while editing goes on.

Journal 0 starts from a base: the project file the session opened or saved (named with its size
and modification time, which must still match), or an empty project. A record is the change from
the previous state (timeline.files.journal_records); a recording's samples are appended once per
content key, before the first record naming it. After `snapshot_records` records or
`snapshot_bytes` bytes the next generation starts: its journal receives the following records,
and when its snapshot is complete the previous generation's files are removed.

Recovery reads the newest snapshot that loads (else journal 0's base) and replays every complete
record after it, generation by generation; a torn or damaged record ends the replay there (what
follows it cannot apply), never with an exception.
"""

from __future__ import annotations

import contextlib
import json
import os
import shutil
import struct
import threading
import zlib
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from timeline.errors import HapticTimelineError, ProjectFileError
from timeline.files import journal_records as records
from timeline.files import media as sample_media
from timeline.files import projectfile
from timeline.files.atomic import write_atomically
from timeline.model import Project
from timeline.tiles import SampledTile

MAGIC = b"haptic-timeline journal 1\n"
HEAD = struct.Struct("<QI")  # a record's payload length and its CRC-32
JSON_LENGTH = struct.Struct("<I")
SNAPSHOT_RECORDS = 500  # records in a generation before the next snapshot is written
SNAPSHOT_BYTES = 64 << 20  # or bytes of its journal
WRITE_CHUNK = 1 << 30  # the most one write() is given
EMPTY = Project()  # the base of a journal whose first record writes the project whole
EMPTY_REPLAY = Project()  # where a replay without a snapshot starts


def journal_path(folder: Path, generation: int) -> Path:
    return folder / f"journal-{generation}.log"


def snapshot_path(folder: Path, generation: int) -> Path:
    return folder / f"snapshot-{generation}.htl"


def _generations(folder: Path, pattern: str) -> list[int]:
    found = []
    for path in folder.glob(pattern.replace("G", "*")):
        with contextlib.suppress(ValueError):
            found.append(int(path.name.split("-", 1)[1].split(".", 1)[0]))
    return sorted(found)


def _write_all(fd: int, parts: list[memoryview]) -> None:
    for part in parts:
        while part:
            done = os.write(fd, part[:WRITE_CHUNK])
            part = part[done:]


def _samples(tile: SampledTile) -> memoryview:
    data = tile.data.astype(tile.data.dtype.newbyteorder("<"), copy=False)
    return memoryview(np.ascontiguousarray(data)).cast("B")  # pyright: ignore[reportArgumentType]


# --- writing -----------------------------------------------------------------------------------


@dataclass
class _Generation:
    number: int
    fd: int
    records: int = 0
    size: int = 0


@dataclass
class Journal:
    """Writes one session's journal and snapshots into `folder` (see the module's docstring).

    `record(project)` appends the change since the last state; `start(...)` begins anew from a
    base; `remove()` deletes the folder (after a save or a clean close). A snapshot that fails
    reports through `failed` (one line) and the journal goes on.
    """

    folder: Path
    snapshot_records: int = SNAPSHOT_RECORDS
    snapshot_bytes: int = SNAPSHOT_BYTES
    failed: Callable[[str], None] = lambda _text: None
    _state: Project | None = None  # the state the last record arrived at
    _meta: dict[str, Any] = field(default_factory=dict)  # meta.json, and journal 0's base
    _generation: _Generation | None = None
    _known: set[str] = field(default_factory=set)  # recordings already in the chain
    _snapshot: threading.Thread | None = None
    _lock: threading.Lock = field(default_factory=threading.Lock)  # held while files go
    _epoch: int = 0  # a snapshot started before the latest removal writes nothing
    _base: Project | None = None  # the state snapshot 0 holds (write_base's), while it is there

    def start(self, base: Project, meta: dict[str, Any], file: Path | None = None) -> None:
        """Begin anew (removing the files so far) from `base`: the content of `file` as it is
        now, or (None) a project the first record writes whole (EMPTY: none). Nothing is
        written until the first record. Starting again at the state `write_base` wrote (an undo
        back to it) keeps that snapshot, so the next first record need not hold it whole."""
        kept = self._base if file is None and base is self._base else None
        self.remove(keep_base=kept is not None)
        self._base = kept
        info: dict[str, Any] = {"file": None}
        if file is not None:
            stat = Path(file).stat()
            info = {"file": str(file), "size": stat.st_size, "mtime_ns": stat.st_mtime_ns}
        self._state, self._meta = base, {**meta, **info}

    @property
    def state(self) -> Project | None:
        """The state the journal is at (its base, before any record)."""
        return self._state

    @property
    def active(self) -> bool:
        """Whether the session has files on disk."""
        return self._generation is not None

    def record(self, project: Project) -> None:
        """Append the change from the last state to `project` (nothing if it is that state)."""
        if self._state is None:
            raise ValueError("the journal was not started")
        if project is self._state:
            return
        if self._generation is None:
            self._open_first()
        doc, media = records.delta(self._state, project)
        for key, tile in media.items():
            if key not in self._known:
                head = {"kind": "media", "key": key, "dtype": sample_media._tag(tile.data)}
                self._append(head, _samples(tile))
                self._known.add(key)
        self._append({"kind": "edit", "change": doc})
        self._state = project
        if self._snapshot_due():
            self._start_snapshot(project)

    def write_base(self) -> None:
        """Write the base now, on a thread, as snapshot 0 (when the journal starts from no file
        and nothing is written yet), so that the first record need not hold the project whole."""
        state = self._state
        if state is None or state is EMPTY or self._meta["file"] is not None or self.active:
            return
        if self.writing or snapshot_path(self.folder, 0).exists():
            return
        self._write_meta()
        self._start_thread(state, 0)

    def _write_meta(self) -> None:
        self.folder.mkdir(parents=True, exist_ok=True)
        text = json.dumps(self._meta).encode("utf-8")

        def write_meta(tmp: Path) -> None:
            tmp.write_bytes(text)

        write_atomically(self.folder / "meta.json", write_meta)

    def _open_first(self) -> None:
        assert self._state is not None
        base, meta = self._state, self._meta
        based = self._base is base and snapshot_path(self.folder, 0).exists()  # write_base's
        self._write_meta()
        self._open_generation(0)
        if based:
            self._known = records.media_keys(base)
            self._append({"kind": "base", "snapshot": 0})
        elif meta["file"] is None:
            self._state = EMPTY  # the first record writes the base whole
            self.record(base)
        else:
            self._known = records.media_keys(base)
            self._append({"kind": "base", **{k: meta[k] for k in ("file", "size", "mtime_ns")}})

    def _open_generation(self, number: int) -> None:
        path = journal_path(self.folder, number)
        flags = os.O_WRONLY | os.O_CREAT | os.O_TRUNC | os.O_APPEND | getattr(os, "O_BINARY", 0)
        fd = os.open(path, flags, 0o600)
        _write_all(fd, [memoryview(MAGIC)])
        if self._generation is not None:
            os.close(self._generation.fd)
        self._generation = _Generation(number, fd, size=len(MAGIC))

    def _append(self, head: dict[str, Any], data: memoryview | None = None) -> None:
        assert self._generation is not None
        text = json.dumps(head, allow_nan=False, separators=(",", ":")).encode("utf-8")
        parts = [memoryview(JSON_LENGTH.pack(len(text))), memoryview(text)]
        if data is not None:
            parts.append(data)
        crc = 0
        for part in parts:
            crc = zlib.crc32(part, crc)
        length = sum(p.nbytes for p in parts)
        _write_all(self._generation.fd, [memoryview(HEAD.pack(length, crc)), *parts])
        self._generation.records += 1
        self._generation.size += HEAD.size + length

    def _snapshot_due(self) -> bool:
        g = self._generation
        return (
            g is not None
            and not self.writing
            and (g.records >= self.snapshot_records or g.size >= self.snapshot_bytes)
        )

    def _start_snapshot(self, project: Project) -> None:
        """Start generation G+1 from `project`: its journal now, its snapshot on a thread."""
        assert self._generation is not None
        number = self._generation.number + 1
        self._open_generation(number)
        self._known = records.media_keys(project)
        self._start_thread(project, number)

    def _start_thread(self, project: Project, number: int) -> None:
        self._snapshot = threading.Thread(
            target=self._write_snapshot,
            args=(project, number, self._epoch),
            name="autosave-snapshot",
            daemon=True,
        )
        self._snapshot.start()

    def _write_snapshot(self, project: Project, number: int, epoch: int) -> None:
        with self._lock:
            if epoch != self._epoch:
                return
            try:
                projectfile.save(project, snapshot_path(self.folder, number))
            except (HapticTimelineError, OSError) as exc:
                reason = exc.strerror if isinstance(exc, OSError) and exc.strerror else exc
                self.failed(f"Autosave snapshot failed: {reason}")
                return
            for older in range(number):
                journal_path(self.folder, older).unlink(missing_ok=True)
                snapshot_path(self.folder, older).unlink(missing_ok=True)
            self._base = project if number == 0 else None

    @property
    def writing(self) -> bool:
        """Whether a snapshot is being written."""
        return self._snapshot is not None and self._snapshot.is_alive()

    def wait(self) -> None:
        """Wait for a snapshot being written (tests and benchmarks)."""
        if self._snapshot is not None:
            self._snapshot.join()

    def remove(self, keep_base: bool = False) -> None:
        """Delete the session's files (`start` begins the next), or all but the base snapshot
        and meta.json (`keep_base`); a snapshot being written is waited for, one not yet
        started will not write."""
        self._epoch += 1
        with self._lock:
            if self._generation is not None:
                os.close(self._generation.fd)
                self._generation = None
            if keep_base:
                kept = {snapshot_path(self.folder, 0).name, "meta.json"}
                for path in self.folder.glob("*"):
                    if path.name not in kept:
                        path.unlink(missing_ok=True)
            else:
                shutil.rmtree(self.folder, ignore_errors=True)
        self._known, self._state, self._base = set(), None, None


# --- reading -----------------------------------------------------------------------------------


def read_records(path: Path) -> Iterator[tuple[dict[str, Any], memoryview]]:
    """The complete records of a journal file in order; stops at a torn or damaged one."""
    try:
        data = path.read_bytes()
    except OSError:
        return
    if not data.startswith(MAGIC):
        return
    view, at = memoryview(data), len(MAGIC)
    while at + HEAD.size <= len(data):
        length, crc = HEAD.unpack_from(data, at)
        start = at + HEAD.size
        if length < JSON_LENGTH.size or start + length > len(data):
            return  # torn: the process was killed while writing it
        payload = view[start : start + length]
        if zlib.crc32(payload) != crc:
            return
        (size,) = JSON_LENGTH.unpack_from(payload)
        try:
            head = json.loads(bytes(payload[JSON_LENGTH.size : JSON_LENGTH.size + size]))
        except (ValueError, UnicodeDecodeError):
            return
        if not isinstance(head, dict):
            return
        yield head, payload[JSON_LENGTH.size + size :]
        at = start + length


def read_meta(folder: Path) -> dict[str, Any]:
    """The session's meta.json ({} if it is missing or damaged)."""
    try:
        meta = json.loads((folder / "meta.json").read_text("utf-8"))
    except (OSError, ValueError):
        return {}
    return meta if isinstance(meta, dict) else {}


@dataclass
class Replay:
    """What recovery found: the project, and how many records it replayed."""

    project: Project
    records: int


def _base_file(head: dict[str, Any], project: Project) -> Project:
    """The project a base record names: its file, or (snapshot 0) `project`, loaded from it."""
    if "snapshot" in head:
        if project is not EMPTY_REPLAY:
            return project
        raise ProjectFileError("the autosave's first snapshot is missing or damaged")
    file = head.get("file")
    if file is None:
        return Project()
    path = Path(str(file))
    try:
        stat = path.stat()
    except OSError:
        raise ProjectFileError(f"the autosave's original {path} is gone") from None
    if (stat.st_size, stat.st_mtime_ns) != (head.get("size"), head.get("mtime_ns")):
        raise ProjectFileError(f"the autosave's original {path} changed since it was made")
    return projectfile.load(path)


def replay(folder: Path) -> Replay:
    """The last state of the session in `folder`: the newest snapshot that loads, or journal 0's
    base, with every complete record after it applied. ProjectFileError (one sentence) when
    there is no state to rebuild, or its base file changed."""
    journals = _generations(folder, "journal-G.log")
    for number in reversed(_generations(folder, "snapshot-G.htl")):
        try:
            project = projectfile.load(snapshot_path(folder, number))
        except ProjectFileError:
            continue  # a damaged one: an older one may load
        replayed = _replayed(folder, project, [g for g in journals if g >= number])
        return replayed if number > 0 else _edited(replayed, folder)  # 0: the base, no edit
    replayed = _replayed(folder, EMPTY_REPLAY, journals) if journals[:1] == [0] else None
    return _edited(replayed, folder)


def _edited(replayed: Replay | None, folder: Path) -> Replay:
    if replayed is None or replayed.records == 0:
        raise ProjectFileError(f"the autosave in {folder} holds no edit")
    return replayed


def _replayed(folder: Path, project: Project, generations: list[int]) -> Replay:
    """`project` with the records of consecutive generations from the first applied."""
    pool = records.media_pool(project)
    count = 0
    for expected, number in enumerate(generations, start=generations[0] if generations else 0):
        if number != expected:
            break  # a generation is missing: nothing after it applies
        for head, data in read_records(journal_path(folder, number)):
            kind = head.get("kind")
            try:
                if kind == "base":
                    project = _base_file(head, project)
                    pool = records.media_pool(project)
                elif kind == "media":
                    dtype = sample_media.DTYPES[str(head.get("dtype"))]
                    native = dtype.newbyteorder("=")  # a copy: the tile owns its samples
                    samples = np.frombuffer(data, dtype=dtype).astype(native)
                    samples.setflags(write=False)
                    pool[str(head.get("key"))] = samples
                elif kind == "edit":
                    project = records.apply(project, head.get("change"), pool)
                    count += 1
            except ProjectFileError:
                raise
            except (HapticTimelineError, KeyError, IndexError, TypeError, ValueError):
                return Replay(project, count)  # a record that does not fit: the end
    return Replay(project, count)
