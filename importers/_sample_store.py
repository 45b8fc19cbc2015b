"""Where an audio reader puts the samples it decodes: float32 when that is exact, hashed as read.

Blocks arrive as float64. They are stored as float32 while every value is a float32 exactly (the
same float64 values come back: 16- and 24-bit PCM, float files, a stereo mix of PCM), and
as float64 from the first block that is not. Each stored block is hashed for the tile's content
key while it is in cache, so nobody hashes the recording again when it is drawn. (Hashing on a
second thread while the next block is decoded was slower on the shared 2-core machine: an hour
of stereo took 3.6-3.9 s wall against 1.8 s, from GIL hand-offs, at the same CPU.)
"""

from __future__ import annotations

import numpy as np

from timeline.signal.memory import require
from timeline.signal.samples import ContentKey, exact_in_float32

# Subtypes whose samples are integers of at most 24 bits (or float32) scaled by a power of two:
# every value read is a float32 exactly. The mean of two channels of the integer ones is too: a
# sum of two 24-bit values is at most 2**24 in magnitude, which float32's 24-bit significand
# holds, and halving it is exact.
_INTEGERS = frozenset({"PCM_S8", "PCM_U8", "PCM_16", "PCM_24", "ULAW", "ALAW"})
_EXACT_ALONE = _INTEGERS | {"FLOAT"}
# Subtypes whose samples are rarely float32 values: stored as float64 from the start.
_WIDE = frozenset({"DOUBLE", "PCM_32"})


def known_exact(subtype: str, mixed_channels: int) -> bool:
    """True if every sample (or mean of `mixed_channels` channels; 1 = one channel kept) of this
    subtype is a float32 exactly, so no block needs checking."""
    if mixed_channels == 1:
        return subtype in _EXACT_ALONE
    return mixed_channels == 2 and subtype in _INTEGERS


class SampleStore:
    """The samples read so far, growing as blocks arrive."""

    def __init__(self, subtype: str, mixed_channels: int, capacity: int, name: str) -> None:
        self.out = np.empty(capacity, dtype=np.float64 if subtype in _WIDE else np.float32)
        self.size = 0
        self.name = name
        self._checked = self.out.dtype == np.float32 and not known_exact(subtype, mixed_channels)
        self._key = ContentKey(self.out.dtype)

    @property
    def exact_float32(self) -> bool:
        """True when the store is float32 and every sample is known to be one exactly: a reader
        may then decode straight into reserve()d slots as float32 (no float64 block, no copy)."""
        return self.out.dtype == np.float32 and not self._checked

    def append(self, part: np.ndarray, total: int) -> None:
        """Store the next samples (float64, or float32 if exact_float32); `total` is the most the
        file can hold."""
        if self._checked and self.out.dtype == np.float32 and not exact_in_float32(part):
            self._moved(np.float64, self.out.size)
        self.reserve(len(part), total)[:] = part
        self.commit(len(part))

    def reserve(self, count: int, total: int) -> np.ndarray:
        """The next `count` slots of the store, to fill in place and then commit()."""
        if self.size + count > self.out.size:
            self._moved(self.out.dtype, min(total, 2 * (self.size + count)))
        return self.out[self.size : self.size + count]

    def commit(self, count: int) -> None:
        """Keep the next `count` reserved slots as samples (and hash them)."""
        self._key.update(self.out[self.size : self.size + count])
        self.size += count

    def _moved(self, dtype: type, size: int) -> None:
        """Copy what is stored into a new array (wider or larger), within the memory available."""
        require(self.out.nbytes + size * np.dtype(dtype).itemsize, f"reading {self.name}")
        bigger = np.empty(size, dtype=dtype)
        bigger[: self.size] = self.out[: self.size]
        if bigger.dtype != self.out.dtype:  # hash again from the start, in the new precision
            self._key = ContentKey(bigger.dtype)
            self._key.update(bigger[: self.size])
        self.out = bigger

    def finish(self, rate: float) -> tuple[np.ndarray, str]:
        """The stored samples, read-only (the tile keeps this array rather than a copy), and
        their content key at `rate`; call once the read has filled the array."""
        self.out.setflags(write=False)
        return self.out, self._key.key(rate)
