"""Sampled tiles' samples in a project file: raw in its binary appendix, or zlib+base64 text.

A saved file (projectfile.save) is its JSON document, then, when it holds recordings, the line
SEPARATOR and the binary appendix: each recording's samples as raw little-endian bytes, which its
media entry finds by offset and length (counted from the first byte after SEPARATOR) and checks
by its content key (a BLAKE2b-128 of the bytes and the rate: the tile's own key, so saving hashes
nothing and loading hashes once). The samples are written straight from the tile's array and read
block by block into the array the loaded tile keeps (no copy, no text). The text form
(projectfile.dumps, the clipboard) and files of schema 3 and older hold each recording as
zlib-compressed base64 text, which is still read.

Samples are little-endian float32 ("<f4") when the tile stores float32 (a recording whose values
are all float32 exactly) and float64 ("<f8") otherwise, so every value comes back bit-identical.
The base64 text is compressed block by block at zlib level 1 above SMALL_BYTES (on 16-bit audio
level 6 took 8x as long for a file 5 % smaller), and read back piece by piece, never past the
declared count (a compression bomb costs nothing).
"""

from __future__ import annotations

import base64
import io
import zlib
from collections.abc import Iterator
from concurrent.futures import Future, ThreadPoolExecutor
from dataclasses import dataclass
from typing import Any, BinaryIO

import numpy as np

from timeline.errors import FieldError
from timeline.files import project_fields as fields
from timeline.signal.memory import require
from timeline.signal.samples import ContentKey
from timeline.tiles import MAX_TILE_SAMPLES

DTYPES = {"<f4": np.dtype("<f4"), "<f8": np.dtype("<f8")}
ENCODING = "zlib+base64"
RAW = "appendix"  # the encoding of samples stored raw in the binary appendix
SEPARATOR = (
    b"=== binary appendix: the raw little-endian samples of the media above; "
    b"each entry's offset and length count from the byte after this line ===\n"
)
FIND_SEPARATOR = b"\n" + SEPARATOR  # never inside JSON text: a raw newline then "="
BLOCK_SAMPLES = 1 << 20  # compressed at a time
PIECE_CHARS = 1 << 16  # of base64 text decoded and inflated at a time (a multiple of 4)
SMALL_BYTES = 1 << 20  # media up to this size are compressed at level 6, larger at level 1
DEFLATE_RATIO = 1032  # deflate never inflates more than this many bytes per input byte
RAW_BLOCK = 1 << 22  # bytes of raw samples written, read and hashed at a time
KEY_PREFIX = "sampled:"


def _tag(data: np.ndarray) -> str:
    return "<f4" if data.dtype == np.float32 else "<f8"


def encode(data: np.ndarray) -> dict[str, Any]:
    """A media entry for a tile's samples (float32 or float64, as stored), as base64 text."""
    text = b"".join(_base64_pieces(data)).decode("ascii")
    return {"dtype": _tag(data), "count": int(data.size), "encoding": ENCODING, "data": text}


def raw_entry(data: np.ndarray, rate: float, key: str, offset: int) -> dict[str, Any]:
    """A media entry for samples written raw at `offset` in the appendix (by write_raw); `key`
    is the tile's content key of `data` at `rate` (timeline.signal.samples.ContentKey)."""
    tag = _tag(data)
    return {
        "dtype": tag,
        "count": int(data.size),
        "rate": float(rate),
        "encoding": RAW,
        "offset": offset,
        "length": int(data.size) * DTYPES[tag].itemsize,
        "blake2b": key.removeprefix(KEY_PREFIX),
    }


def write_raw(data: np.ndarray, out: BinaryIO) -> None:
    """Write the samples as raw little-endian bytes, straight from the array, block by block."""
    dtype = DTYPES[_tag(data)]
    step = RAW_BLOCK // dtype.itemsize
    for first in range(0, len(data), step):
        block = np.ascontiguousarray(data[first : first + step], dtype=dtype)  # a view, usually
        # an ndarray is a buffer: numpy's stubs declare __buffer__ for Python >= 3.12 only
        out.write(memoryview(block).cast("B"))  # pyright: ignore[reportArgumentType]


def _base64_pieces(data: np.ndarray) -> Iterator[bytes]:
    """The compressed samples as base64, in pieces whose concatenation is one base64 text."""
    tag = _tag(data)
    packer = zlib.compressobj(6 if data.nbytes <= SMALL_BYTES else 1)
    carry = b""
    for first in range(0, len(data), BLOCK_SAMPLES):
        block = np.ascontiguousarray(data[first : first + BLOCK_SAMPLES], dtype=tag)
        # an ndarray is a buffer: numpy's stubs declare __buffer__ for Python >= 3.12 only
        packed = carry + packer.compress(block)  # pyright: ignore[reportArgumentType]
        whole = len(packed) - len(packed) % 3  # base64 of whole 3-byte groups joins seamlessly
        yield base64.b64encode(packed[:whole])
        carry = packed[whole:]
    yield base64.b64encode(carry + packer.flush())


def decode(entry: Any, where: str) -> np.ndarray:
    """The samples of a media entry as a read-only array of their precision; FieldError if the
    entry is damaged or holds other than the count it declares."""
    dtype = DTYPES.get(fields.get(entry, "dtype", str, where))
    if dtype is None or fields.get(entry, "encoding", str, where) != ENCODING:
        raise FieldError(f"{where} uses an unknown sample encoding")
    count = fields.get(entry, "count", int, where)
    if not 0 < count <= MAX_TILE_SAMPLES:
        raise FieldError(f"{where} declares {count} samples, outside the supported range")
    text = fields.get(entry, "data", str, where)
    size = count * dtype.itemsize
    if size > DEFLATE_RATIO * len(text) + 64:  # more than any deflate stream of this size holds
        raise FieldError(f"{where} declares {count} samples but holds fewer")
    require(size, f"opening {where}")
    out = np.empty(count, dtype=dtype)
    # an ndarray is a buffer: numpy's stubs declare __buffer__ for Python >= 3.12 only
    view = memoryview(out).cast("B")  # pyright: ignore[reportArgumentType]
    filled = _inflate(_unpacked(text, where), view, where, count)
    if filled < size:
        raise FieldError(f"{where} holds {filled // dtype.itemsize} samples but declares {count}")
    if not out.dtype.isnative:
        out = out.astype(out.dtype.newbyteorder("="))
    out.setflags(write=False)  # the tile keeps this array rather than a copy
    return out


def _unpacked(text: str, where: str) -> Iterator[bytes]:
    """The bytes of base64 text, PIECE_CHARS characters at a time (no copy of the whole)."""
    try:
        for first in range(0, len(text), PIECE_CHARS):
            yield base64.b64decode(text[first : first + PIECE_CHARS], validate=True)
    except ValueError:
        raise FieldError(f"{where} holds damaged sample data") from None


def _inflate(pieces: Iterator[bytes], out: memoryview, where: str, count: int) -> int:
    """Inflate into out, never more than it holds; the number of bytes filled."""
    inflater = zlib.decompressobj()
    filled = 0
    try:
        for packed in pieces:
            room = len(out) - filled
            piece = inflater.decompress(packed, room + 1)
            if len(piece) > room:
                raise FieldError(f"{where} declares {count} samples but holds more")
            out[filled : filled + len(piece)] = piece
            filled += len(piece)
    except zlib.error:
        raise FieldError(f"{where} holds damaged sample data") from None
    if not inflater.eof and filled == len(out):
        raise FieldError(f"{where} holds damaged sample data")
    return filled


# --- the binary appendix -----------------------------------------------------------------------


@dataclass(frozen=True)
class Appendix:
    """A file's binary appendix: `size` bytes from `start` to the end of `file`."""

    file: io.BufferedIOBase
    start: int
    size: int


SCAN_BYTES = 1 << 20  # read at a time while looking for the end of the JSON document


def split(file: io.BufferedIOBase) -> tuple[bytearray, Appendix | None]:
    """The JSON document's bytes, and the appendix after SEPARATOR if the file has one.

    Reads the file from its start until SEPARATOR (or the end): never into the appendix.
    """
    text = bytearray()
    while True:
        piece = file.read(SCAN_BYTES)
        if not piece:
            return text, None
        seen = max(0, len(text) - len(FIND_SEPARATOR) + 1)
        text += piece
        at = text.find(FIND_SEPARATOR, seen)
        if at >= 0:
            start = at + len(FIND_SEPARATOR)
            end = file.seek(0, 2)
            del text[at + 1 :]  # the JSON keeps its last newline
            return text, Appendix(file, start, end - start)


def check_size(appendix: Appendix | None, declared: Any) -> None:
    """FieldError unless the appendix holds exactly the bytes the document declares (`declared`:
    the document's "appendix" value, None when it has none)."""
    if declared is None:
        if appendix is not None:
            raise FieldError("it has a binary appendix that its project does not declare")
        return
    size = fields.integer(declared, "bytes", "the file's appendix", 0, 2**62)
    if appendix is None:
        raise FieldError(f"it is truncated: its binary appendix of {size} bytes is missing")
    if appendix.size < size:
        raise FieldError(
            f"it is truncated: its binary appendix holds {appendix.size} of the {size} bytes "
            "its project declares"
        )
    if appendix.size > size:
        raise FieldError(
            f"it has {appendix.size - size} unexpected bytes after its binary appendix"
        )


def samples_of(
    entry: Any, where: str, appendix: Appendix | None
) -> tuple[np.ndarray, ContentKey | None]:
    """The samples of a media entry of either encoding, with their ContentKey when they were
    hashed while read (raw samples); FieldError if the entry is damaged."""
    if fields.obj(entry, where).get("encoding") != RAW:
        return decode(entry, where), None
    if appendix is None:
        raise FieldError(f"{where} is stored in a binary appendix, which the file does not have")
    return read_raw(entry, where, appendix)


def read_raw(entry: Any, where: str, appendix: Appendix) -> tuple[np.ndarray, ContentKey]:
    """Raw samples from the appendix into a fresh read-only array, each block checked finite and
    hashed as it arrives; FieldError unless they are what the entry declares and its hash."""
    dtype = DTYPES.get(fields.get(entry, "dtype", str, where))
    if dtype is None:
        raise FieldError(f"{where} uses an unknown sample encoding")
    count = fields.integer(entry, "count", where, 1, MAX_TILE_SAMPLES)
    rate = fields.number(entry, "rate", where, positive=True)
    offset = fields.integer(entry, "offset", where, 0, 2**62)
    length = fields.integer(entry, "length", where, 0, 2**62)
    digest = fields.get(entry, "blake2b", str, where)
    if length != count * dtype.itemsize:
        raise FieldError(f"{where} holds {length // dtype.itemsize} samples but declares {count}")
    if offset + length > appendix.size:
        raise FieldError(f"{where} lies past the end of the binary appendix")
    require(length, f"opening {where}")
    out = np.empty(count, dtype=dtype)
    key = ContentKey(out.dtype)
    appendix.file.seek(appendix.start + offset)
    _read_hashed(appendix.file, out, key, where)
    if key.key(rate) != KEY_PREFIX + digest:
        raise FieldError(f"{where} is damaged: its samples do not match their hash")
    if not out.dtype.isnative:
        out = out.astype(out.dtype.newbyteorder("="))
    out.setflags(write=False)  # the tile keeps this array rather than a copy
    return out, key


def _read_hashed(file: io.BufferedIOBase, out: np.ndarray, key: ContentKey, where: str) -> None:
    """Fill `out` from the file block by block; a thread hashes each block while the next is
    read (both release the interpreter lock), and each is checked finite."""
    # an ndarray is a buffer: numpy's stubs declare __buffer__ for Python >= 3.12 only
    view = memoryview(out).cast("B")  # pyright: ignore[reportArgumentType]
    step = RAW_BLOCK // out.itemsize
    with ThreadPoolExecutor(1, thread_name_prefix="media-hash") as hasher:
        hashed: Future | None = None
        for first in range(0, out.size, step):
            block = out[first : first + step]
            if file.readinto(view[first * out.itemsize : (first + block.size) * out.itemsize]) != (
                block.nbytes
            ):
                raise FieldError(f"{where} lies past the end of the file")
            if not np.isfinite(block).all():
                bad = first + int(np.flatnonzero(~np.isfinite(block))[0])
                raise FieldError(f"{where}: sample {bad} is not a finite number")
            if hashed is not None:
                hashed.result()
            hashed = hasher.submit(key.update, block)
        if hashed is not None:
            hashed.result()
