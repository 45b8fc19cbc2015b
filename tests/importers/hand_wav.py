"""A 16-bit PCM WAV built byte by byte from its header fields (no audio library writes it).

It stands in for the corpus's recordings where a test needs only a WAV made without our code or
soundfile: a mono file and a stereo one whose samples, and so their stored values (integer /
32768, the stereo channels' mean), are known exactly.
"""

from __future__ import annotations

import struct
from pathlib import Path

RATE = 44_100
# (left, right) 16-bit samples, and each frame's value as stored: the mean over 32768
STEREO = [(0, 0), (16384, 16384), (-16384, 0), (32767, 32767), (-32768, -32768), (1, 2)]
STEREO_VALUES = [0.0, 0.5, -0.25, 32767 / 32768, -1.0, 1.5 / 32768]
MONO = [0, 8192, -8192, 32767, -32768, -1]
MONO_VALUES = [0.0, 0.25, -0.25, 32767 / 32768, -1.0, -1 / 32768]


def write_wav(path: Path, frames: list[tuple[int, ...]] | list[int]) -> Path:
    """A canonical 44-byte-header WAV: RIFF, a 16-byte `fmt ` chunk (PCM, format 1), `data`."""
    rows = [f if isinstance(f, tuple) else (f,) for f in frames]
    channels = len(rows[0])
    samples = [s for row in rows for s in row]
    data = struct.pack(f"<{len(samples)}h", *samples)
    block = 2 * channels
    fmt = struct.pack("<HHIIHH", 1, channels, RATE, RATE * block, block, 16)
    body = b"WAVE" + b"fmt " + struct.pack("<I", len(fmt)) + fmt
    body += b"data" + struct.pack("<I", len(data)) + data
    path.write_bytes(b"RIFF" + struct.pack("<I", len(body)) + body)
    return path
