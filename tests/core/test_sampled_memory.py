"""Long recordings: a tile keeps a reader's fresh read-only array, copies anything else."""

from __future__ import annotations

import hashlib

import numpy as np
import soundfile as sf

from importers.audio import AudioFormat
from timeline.tiles import SampledTile


def test_a_fresh_read_only_array_is_kept_and_anything_else_copied():
    fresh = np.linspace(-1, 1, 1000).copy()  # owns its memory, as a reader's array does
    fresh.setflags(write=False)
    assert SampledTile(fresh, 100.0).data is fresh
    writable = np.linspace(-1, 1, 1000)
    tile = SampledTile(writable, 100.0)
    writable[0] = 5.0
    assert tile.data is not writable and tile.data[0] == -1.0
    view = fresh[::2]
    assert SampledTile(view, 100.0).data is not view
    as_float32 = np.linspace(-1, 1, 10, dtype=np.float32)
    as_float32.setflags(write=False)
    assert SampledTile(as_float32, 10.0).data.dtype == np.float64


def test_the_key_hashes_the_samples_as_before():
    data = np.sin(np.arange(5000) * 0.01)
    tile = SampledTile(data, 1000.0)
    h = hashlib.blake2b(data.tobytes(), digest_size=16)
    h.update(repr(1000.0).encode())
    assert tile.key == "sampled:" + h.hexdigest()


def test_a_wav_read_is_the_tiles_own_array(tmp_path):
    path = tmp_path / "tone.wav"
    samples = (0.5 * np.sin(np.arange(44_100) * 0.05)).astype(np.float32)
    sf.write(path, samples, 44_100, subtype="PCM_24")
    tile = AudioFormat().read(path)
    assert tile.data.base is None and not tile.data.flags.writeable
    np.testing.assert_allclose(tile.data, samples, atol=2**-23)
