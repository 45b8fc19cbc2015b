"""Long recordings: a tile keeps a reader's fresh read-only array (float64 or float32), copies
anything else, and scans and hashes its samples in blocks."""

from __future__ import annotations

import hashlib

import numpy as np
import pytest
import soundfile as sf

from importers.audio import AudioFormat
from timeline.errors import EditError
from timeline.signal import samples
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
    assert SampledTile(as_float32, 10.0).data.dtype == np.float64  # writable: a float64 copy
    as_float32.setflags(write=False)
    assert SampledTile(as_float32, 10.0).data is as_float32  # a reader's float32 store is kept


def test_non_finite_samples_are_found_block_by_block(monkeypatch):
    monkeypatch.setattr(samples, "BLOCK", 100)
    data = np.zeros(1000, dtype=np.float32)
    assert samples.first_non_finite(data) is None
    data[[731, 950]] = [np.inf, np.nan]
    assert samples.first_non_finite(data) == 731
    data.setflags(write=False)
    with pytest.raises(EditError, match=r"^sample 731 of tile 'sampled' is not a finite number$"):
        SampledTile(data, 10.0)


def test_the_key_is_hashed_in_blocks_and_marks_float32(monkeypatch):
    monkeypatch.setattr(samples, "BLOCK", 64)
    data = np.sin(np.arange(1000) * 0.01).astype(np.float32)
    h = hashlib.blake2b(data.tobytes(), digest_size=16)
    h.update(repr(100.0).encode())
    h.update(b"float32")
    data.setflags(write=False)
    assert SampledTile(data, 100.0).key == "sampled:" + h.hexdigest()


def test_a_checked_tile_takes_only_a_readers_own_frozen_samples():
    fresh = np.ones(10, dtype=np.float32)
    with pytest.raises(EditError, match="read-only"):
        SampledTile.from_checked(fresh, 10.0, "x", "")  # writable: someone else may change it
    fresh.setflags(write=False)
    tile = SampledTile.from_checked(fresh, 10.0, "x", "", "sampled:given")
    assert tile.data is fresh and tile.key == "sampled:given"
    renamed = tile.with_name("y")
    assert renamed.data is fresh and renamed.key == tile.key and renamed.name == "y"


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
