"""Sampled tiles' samples in a project file: zlib-compressed base64 text, in their own precision.

Samples are written as little-endian float32 ("<f4") when the tile stores float32 (a recording
whose values are all float32 exactly) and float64 ("<f8") otherwise, so every value comes back
bit-identical. They are compressed block by block straight from the tile's array and written to
the file as base64 in pieces (no float64, bytes or text copy of an hour), at zlib level 1 above
SMALL_BYTES (on 16-bit audio level 6 took 8x as long for a file 5 % smaller), and read back
piece by piece into the array the loaded tile keeps, never past the declared count (a
compression bomb costs nothing).
"""

from __future__ import annotations

import base64
import zlib
from collections.abc import Iterator
from typing import Any, BinaryIO

import numpy as np

from timeline.errors import FieldError
from timeline.files import project_fields as fields
from timeline.signal.memory import require
from timeline.tiles import MAX_TILE_SAMPLES

DTYPES = {"<f4": np.dtype("<f4"), "<f8": np.dtype("<f8")}
ENCODING = "zlib+base64"
BLOCK_SAMPLES = 1 << 20  # compressed at a time
PIECE_CHARS = 1 << 16  # of base64 text decoded and inflated at a time (a multiple of 4)
SMALL_BYTES = 1 << 20  # media up to this size are compressed at level 6, larger at level 1
DEFLATE_RATIO = 1032  # deflate never inflates more than this many bytes per input byte


def header(data: np.ndarray, text: str) -> dict[str, Any]:
    """A media entry for a tile's samples (float32 or float64, as stored) with `text` as its
    data: a placeholder that a streaming writer replaces with write_base64(data)."""
    tag = "<f4" if data.dtype == np.float32 else "<f8"
    return {"dtype": tag, "count": int(data.size), "encoding": ENCODING, "data": text}


def encode(data: np.ndarray) -> dict[str, Any]:
    """A media entry for a tile's samples, its data as one string."""
    return header(data, b"".join(_base64_pieces(data)).decode("ascii"))


def write_base64(data: np.ndarray, out: BinaryIO) -> None:
    """Write the base64 text of encode(data)["data"] to a binary file, block by block."""
    for piece in _base64_pieces(data):
        out.write(piece)


def _base64_pieces(data: np.ndarray) -> Iterator[bytes]:
    """The compressed samples as base64, in pieces whose concatenation is one base64 text."""
    tag = header(data, "")["dtype"]
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
