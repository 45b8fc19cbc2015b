"""A sound kept by `convert` is read block by block into the one float32 array its tile keeps."""

from __future__ import annotations

import numpy as np
import soundfile as sf

from timeline.analysis import source
from timeline.files.convert import analyse_sound_file
from timeline.tiles import SampledTile


def test_the_mono_mix_fills_one_read_only_float32_array(tmp_path, monkeypatch):
    monkeypatch.setattr(source, "BLOCK_FRAMES", 1000)  # several blocks and a short last one
    stereo = np.random.default_rng(4).uniform(-0.5, 0.5, (4321, 2))
    path = tmp_path / "stereo.wav"
    sf.write(path, stereo, 8000, subtype="PCM_16")
    read = sf.read(path, dtype="float32")[0]
    mono = source.mono_samples(path)
    assert mono.dtype == np.float32 and not mono.flags.writeable and mono.base is None
    np.testing.assert_array_equal(mono, read @ np.full(2, 0.5, dtype=np.float32))
    converted = analyse_sound_file(path)
    tile = SampledTile(converted.sound, 8000.0)
    assert tile.data is converted.sound  # kept as it is: no float64 copy
