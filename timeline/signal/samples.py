"""Sample arrays of sampled tiles: their precision, content key and finiteness, in blocks.

A recording is stored as float32 when every one of its values is a float32 exactly (16- and
24-bit PCM, float WAV, a stereo mix of PCM), else as float64, so an hour at 44.1 kHz
costs 0.64 GB instead of 1.27 GB and reads back the same float64 values. Scans work on blocks
of BLOCK samples, so no pass makes a full-size temporary (a boolean mask of an hour is 159 MB).
"""

from __future__ import annotations

import numpy as np

BLOCK = 1 << 20
STORED_DTYPES = (np.dtype(np.float64), np.dtype(np.float32))


def frozen(data: object) -> bool:
    """True for a read-only 1-D float64 or float32 array that owns its memory (a reader's fresh
    array): nobody else can change it, so a tile can keep it instead of a copy."""
    return (
        isinstance(data, np.ndarray)
        and data.dtype in STORED_DTYPES
        and data.ndim == 1
        and data.base is None
        and data.flags.c_contiguous
        and not data.flags.writeable
    )


def exact_in_float32(block: np.ndarray) -> bool:
    """True if every value of a float64 block is a float32 exactly (it round-trips)."""
    return bool(np.array_equal(block.astype(np.float32), block))


def first_non_finite(data: np.ndarray) -> int | None:
    """Index of the first NaN or infinite sample, or None; checked block by block."""
    for first in range(0, len(data), BLOCK):
        block = data[first : first + BLOCK]
        if not np.isfinite(block).all():
            return first + int(np.flatnonzero(~np.isfinite(block))[0])
    return None


class ContentKey:
    """The content key of a tile's samples, fed block by block as a reader makes them.

    blake2b over the stored bytes and the rate; float32 samples are marked, so a float32 and a
    float64 store of the same values have different keys (they are different tiles: see
    SampledTile.__eq__). A float64 tile's key is what it was before float32 stores existed.
    """

    def __init__(self, dtype: np.dtype) -> None:
        import hashlib  # with the first recording, not at start-up (~3 ms)

        self.dtype = np.dtype(dtype)
        self._hash = hashlib.blake2b(digest_size=16)

    def update(self, block: np.ndarray) -> None:
        """Add the next samples (of this key's dtype, C-contiguous; hashed in place)."""
        # an ndarray is a buffer: numpy's stubs declare __buffer__ for Python >= 3.12 only
        self._hash.update(memoryview(block).cast("B"))  # pyright: ignore[reportArgumentType]

    def key(self, rate: float) -> str:
        h = self._hash.copy()
        h.update(repr(float(rate)).encode())
        if self.dtype == np.float32:
            h.update(b"float32")
        return "sampled:" + h.hexdigest()


def content_key(data: np.ndarray, rate: float) -> str:
    """The ContentKey of a whole stored array (hashed in place, in blocks)."""
    digest = ContentKey(data.dtype)
    for first in range(0, len(data), BLOCK):
        digest.update(data[first : first + BLOCK])
    return digest.key(rate)
