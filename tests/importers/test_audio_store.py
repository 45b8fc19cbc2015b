"""Recordings stored as float32 where that is exact: the same values, renders and keys as float64.

An hour at 44.1 kHz is 1.27 GB as float64 and 0.64 GB as float32; these tests prove on small
files that the narrower store changes no rendered sample, that the content key computed while
reading is the key of the stored samples and changes with them, and that bad samples are still
refused in one sentence.
"""

from __future__ import annotations

import numpy as np
import pytest
import soundfile as sf

from importers import audio
from importers._sample_store import known_exact
from timeline import edits
from timeline.plugins.file_formats import FormatError
from timeline.rendering import mixer
from timeline.signal.render_presets import PRESETS, QualityPreset
from timeline.signal.samples import content_key
from timeline.tiles import SampledTile

from .hand_wav import MONO, MONO_VALUES, STEREO, STEREO_VALUES, write_wav

RNG = np.random.default_rng(11)
CUBIC = QualityPreset("cubic", "linear", "cubic", 1, "float64")


def _pcm(bits: int, n: int, channels: int) -> np.ndarray:
    top = 2 ** (bits - 1)
    return RNG.integers(-top, top, size=(n, channels)) / top


def _expected(path, channel: int | None) -> np.ndarray:
    """What the float64 reader gave before: one channel, or the mean of all."""
    data = sf.read(path, dtype="float64", always_2d=True)[0]
    return data.mean(axis=1) if channel is None else data[:, channel - 1]


CASES = [
    # (subtype, channels, channel to keep (None: the mix), stored dtype)
    ("PCM_16", 1, None, np.float32),
    ("PCM_24", 1, None, np.float32),
    ("PCM_U8", 1, None, np.float32),
    ("PCM_16", 2, None, np.float32),  # (a + b) / 2 of 16-bit values: 17 bits, exact
    ("PCM_24", 2, 2, np.float32),
    ("PCM_24", 2, None, np.float32),  # a sum of two 24-bit values fits float32's significand
    ("FLOAT", 2, None, np.float64),  # the mean of two float32 mostly does not: checked, widened
    ("PCM_16", 3, None, np.float64),  # a third is no float32 either
    ("FLOAT", 1, None, np.float32),
    ("DOUBLE", 1, None, np.float64),
    ("PCM_32", 1, None, np.float64),
]


@pytest.mark.parametrize(("subtype", "channels", "channel", "dtype"), CASES)
def test_the_store_holds_the_float64_values_exactly(tmp_path, subtype, channels, channel, dtype):
    path = tmp_path / "x.wav"
    bits = {"PCM_U8": 8, "PCM_16": 16, "PCM_24": 24, "PCM_32": 32}.get(subtype, 24)
    data = _pcm(bits, 3000, channels)
    if subtype in ("FLOAT", "DOUBLE"):
        data = RNG.uniform(-1, 1, (3000, channels))
        data[:, 0] *= 1e-3  # channels of other magnitudes: their float32 mean needs rounding
    sf.write(path, data, 8000, subtype=subtype)
    tile = audio.FORMAT.read(path, channel=channel)
    assert tile.data.dtype == dtype
    np.testing.assert_array_equal(tile.data.astype(np.float64), _expected(path, channel))
    assert tile.key == content_key(tile.data, tile.rate)  # hashed while reading = hashed after


@pytest.mark.parametrize("quality", [*PRESETS.values(), CUBIC], ids=lambda q: q.name)
def test_a_float32_store_renders_bit_identical_to_float64(tmp_path, quality):
    path = tmp_path / "x.wav"
    sf.write(path, _pcm(24, 20_000, 1), 44_100, subtype="PCM_24")
    narrow = audio.FORMAT.read(path)
    wide = SampledTile(narrow.data.astype(np.float64), narrow.rate)
    assert narrow.data.dtype == np.float32
    for u0, du, n in [
        (0.0, 1 / 44_100, 5000),  # on the grid: copied
        (0.0123, 1 / 10_000, 2000),  # off-grid, resampled to 10 kHz
        (0.05, 1 / 3_000, 600),
        (0.3, -1 / 10_000, 1000),  # reversed
        (0.4, 1 / 10_000, 1000),  # running past the end: zeros
    ]:
        got = narrow.render(u0, du, n, quality)
        assert got.dtype == np.float64
        np.testing.assert_array_equal(got, wide.render(u0, du, n, quality))


def test_a_project_mix_of_a_16_bit_stereo_recording_is_unchanged(tmp_path):
    path = tmp_path / "stereo.wav"
    sf.write(path, _pcm(16, 30_000, 2), 48_000, subtype="PCM_16")
    narrow = audio.FORMAT.read(path)
    wide = SampledTile(narrow.data.astype(np.float64), narrow.rate, narrow.name, narrow.source)
    mixes = []
    for tile in (narrow, wide):
        project, tile_id = edits.add_tile(edits.new_project(), tile)
        project, track = edits.add_track(project, "drive")
        project, _ = edits.add_clip(project, track, tile_id, 0.0137, stretch=1.3, gain=0.8)
        mixes.append(mixer.render(project)["drive"])
    assert np.abs(mixes[0]).max() > 0.1
    np.testing.assert_array_equal(mixes[0], mixes[1])


@pytest.mark.parametrize("channels", [2, 3, 6])
def test_the_mix_is_np_mean_bit_for_bit_signed_zeros_included(tmp_path, channels):
    data = RNG.uniform(-1, 1, (4000, channels))
    data[:100] = -0.0
    data[100:200, 0] = 0.0
    path = tmp_path / "mix.wav"
    sf.write(path, data, 8000, subtype="DOUBLE")
    got = audio.FORMAT.read(path).data
    assert got.tobytes() == np.mean(data, axis=1).tobytes()


def test_a_mix_that_stops_being_exact_midway_is_widened_and_rehashed(tmp_path, monkeypatch):
    monkeypatch.setattr(audio, "BLOCK_FRAMES", 1000)
    same = np.repeat(_pcm(16, 2500, 1), 3, axis=1)  # three equal channels: the mean is exact
    path = tmp_path / "three.wav"
    sf.write(path, np.vstack([same, _pcm(16, 2500, 3)]), 8000, subtype="PCM_16")
    tile = audio.FORMAT.read(path)
    assert tile.data.dtype == np.float64
    np.testing.assert_array_equal(tile.data, _expected(path, None))
    assert tile.key == content_key(tile.data, 8000.0)


def test_the_key_changes_with_one_sample_and_not_with_a_second_read(tmp_path):
    data = _pcm(16, 5000, 1)
    first, second = tmp_path / "a.wav", tmp_path / "b.wav"
    sf.write(first, data, 44_100, subtype="PCM_16")
    data[-1, 0] += 2**-15  # one least significant bit, in the last block
    sf.write(second, data, 44_100, subtype="PCM_16")
    a, again, b = (audio.FORMAT.read(p) for p in (first, first, second))
    assert a.key == again.key and a == again
    assert a.key != b.key and a != b
    assert a.key != SampledTile(a.data.astype(np.float64), a.rate).key  # float64 is another tile


def test_a_float_wav_with_nan_is_refused_in_one_sentence(tmp_path, monkeypatch):
    monkeypatch.setattr(audio, "BLOCK_FRAMES", 1000)
    data = RNG.uniform(-1, 1, 5000).astype(np.float32)
    data[3456] = np.nan
    path = tmp_path / "nan.wav"
    sf.write(path, data, 8000, subtype="FLOAT")
    with pytest.raises(FormatError) as caught:
        audio.FORMAT.read(path)
    assert str(caught.value) == "nan.wav has a sample that is not a finite number (frame 3456)"


def test_only_sums_of_few_enough_bits_skip_the_exactness_check():
    assert known_exact("PCM_24", 1) and known_exact("PCM_24", 2) and known_exact("FLOAT", 1)
    assert not known_exact("PCM_16", 3)
    assert not known_exact("FLOAT", 2) and not known_exact("PCM_32", 1)


def test_corpus_recordings_are_stored_exactly(corpus):
    wavs = sorted((corpus / "audio-pairs").glob("*.wav"))
    assert wavs
    for path in wavs:
        tile = audio.FORMAT.read(path)
        assert tile.data.dtype == np.float32, path.name
        np.testing.assert_array_equal(tile.data.astype(np.float64), _expected(path, None))


@pytest.mark.parametrize(("frames", "values"), [(MONO, MONO_VALUES), (STEREO, STEREO_VALUES)])
def test_a_wav_built_by_hand_is_stored_as_its_samples_over_32768(tmp_path, frames, values):
    """The corpus test's claim on a file no audio library wrote: values known without one."""
    tile = audio.FORMAT.read(write_wav(tmp_path / "hand.wav", frames))
    assert tile.data.dtype == np.float32 and tile.rate == 44_100
    assert tile.data.astype(np.float64).tolist() == values


@pytest.mark.parametrize("container", ["FLAC", "AIFF", "WAV"])
def test_one_channel_decoded_straight_into_the_store_is_exact(tmp_path, container, monkeypatch):
    monkeypatch.setattr(audio, "BLOCK_FRAMES", 1000)  # several blocks, the last one partial
    path = tmp_path / f"mono.{container.lower()}"
    sf.write(path, _pcm(24, 4321, 1), 22_050, subtype="PCM_24", format=container)
    tile = audio.FORMAT.read(path)
    assert tile.data.dtype == np.float32
    np.testing.assert_array_equal(tile.data.astype(np.float64), _expected(path, None))
    assert tile.key == content_key(tile.data, 22_050.0)
