"""Sampled tiles' samples in a project file: zlib-compressed base64 text, in their own precision.

Samples are written as little-endian float32 ("<f4") when the tile stores float32 (a recording
whose values are all float32 exactly) and float64 ("<f8") otherwise, so every value comes back
bit-identical. They are compressed block by block straight from the tile's array (no float64 or
bytes copy of an hour), at zlib level 1 above SMALL_BYTES (on an hour of 16-bit audio level 6
took 8x as long for a file 5 % smaller), and inflated straight into the array the loaded tile
keeps, never past the declared count (a compression bomb costs nothing).
"""

from __future__ import annotations

import base64
import zlib
from typing import Any

import numpy as np

from timeline import project_fields as fields
from timeline.memory import require
from timeline.project_fields import FieldError
from timeline.tiles import MAX_TILE_SAMPLES

DTYPES = {"<f4": np.dtype("<f4"), "<f8": np.dtype("<f8")}
ENCODING = "zlib+base64"
BLOCK_SAMPLES = 1 << 20  # compressed at a time
PIECE_BYTES = 1 << 16  # of compressed input inflated at a time
SMALL_BYTES = 1 << 20  # media up to this size are compressed at level 6, larger at level 1
DEFLATE_RATIO = 1032  # deflate never inflates more than this many bytes per input byte


def encode(data: np.ndarray) -> dict[str, Any]:
    """A media entry for a tile's samples (float32 or float64, as stored)."""
    tag = "<f4" if data.dtype == np.float32 else "<f8"
    packer = zlib.compressobj(6 if data.nbytes <= SMALL_BYTES else 1)
    packed = [
        packer.compress(np.ascontiguousarray(data[first : first + BLOCK_SAMPLES], dtype=tag))
        for first in range(0, len(data), BLOCK_SAMPLES)
    ]
    packed.append(packer.flush())
    return {
        "dtype": tag,
        "count": int(data.size),
        "encoding": ENCODING,
        "data": base64.b64encode(b"".join(packed)).decode("ascii"),
    }


def decode(entry: Any, where: str) -> np.ndarray:
    """The samples of a media entry as a read-only array of their precision; FieldError if the
    entry is damaged or holds other than the count it declares."""
    dtype = DTYPES.get(fields.get(entry, "dtype", str, where))
    if dtype is None or fields.get(entry, "encoding", str, where) != ENCODING:
        raise FieldError(f"{where} uses an unknown sample encoding")
    count = fields.get(entry, "count", int, where)
    if not 0 < count <= MAX_TILE_SAMPLES:
        raise FieldError(f"{where} declares {count} samples, outside the supported range")
    try:
        packed = base64.b64decode(fields.get(entry, "data", str, where), validate=True)
    except ValueError:
        raise FieldError(f"{where} holds damaged sample data") from None
    size = count * dtype.itemsize
    if size > DEFLATE_RATIO * len(packed) + 64:  # more than any deflate stream of this size holds
        raise FieldError(f"{where} declares {count} samples but holds fewer")
    require(size, f"opening {where}")
    out = np.empty(count, dtype=dtype)
    filled = _inflate(packed, memoryview(out).cast("B"), where, count)
    if filled < size:
        raise FieldError(f"{where} holds {filled // dtype.itemsize} samples but declares {count}")
    if not out.dtype.isnative:
        out = out.astype(out.dtype.newbyteorder("="))
    out.setflags(write=False)  # the tile keeps this array rather than a copy
    return out


def _inflate(packed: bytes, out: memoryview, where: str, count: int) -> int:
    """Inflate into out, never more than it holds; the number of bytes filled."""
    inflater = zlib.decompressobj()
    source = memoryview(packed)
    filled = 0
    try:
        for first in range(0, len(packed), PIECE_BYTES):
            room = len(out) - filled
            piece = inflater.decompress(source[first : first + PIECE_BYTES], room + 1)
            if len(piece) > room:
                raise FieldError(f"{where} declares {count} samples but holds more")
            out[filled : filled + len(piece)] = piece
            filled += len(piece)
    except zlib.error:
        raise FieldError(f"{where} holds damaged sample data") from None
    if not inflater.eof and filled == len(out):
        raise FieldError(f"{where} holds damaged sample data")
    return filled
