"""Audio import: every soundfile subtype read back exactly, channels, long files, bad input."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import soundfile as sf

from importers import audio
from timeline.edits import new_project
from timeline.files import exporting, importing
from timeline.plugins.file_formats import FormatError
from timeline.rendering import mixer

RNG = np.random.default_rng(7)
SCIPY_DATA = Path(np.__file__).parents[1] / "scipy" / "io" / "tests" / "data"


def _levels(bits: int, n: int = 500, channels: int = 1) -> np.ndarray:
    """Values exactly representable at a bit depth: integers over 2**(bits-1)."""
    top = 2 ** (bits - 1)
    return RNG.integers(-top, top, size=(n, channels)) / top


EXACT = [
    ("WAV", "PCM_U8", 8),
    ("WAV", "PCM_16", 16),
    ("WAV", "PCM_24", 24),
    ("WAV", "PCM_32", 32),
    ("WAVEX", "PCM_24", 24),
    ("RF64", "PCM_16", 16),
    ("FLAC", "PCM_16", 16),
    ("FLAC", "PCM_24", 24),
    ("AIFF", "PCM_16", 16),
    ("AIFF", "PCM_24", 24),
]


@pytest.mark.parametrize(("container", "subtype", "bits"), EXACT)
def test_integer_subtypes_read_back_exactly(tmp_path, container, subtype, bits):
    data = _levels(bits, channels=2)
    ext = {"WAVEX": "wav", "RF64": "wav", "AIFF": "aiff"}.get(container, container.lower())
    path = tmp_path / f"x.{ext}"
    sf.write(path, data, 8000, subtype=subtype, format=container)
    tile = audio.FORMAT.read(path, channel=2)
    assert tile.rate == 8000
    np.testing.assert_array_equal(tile.data, data[:, 1])


@pytest.mark.parametrize("subtype", ["FLOAT", "DOUBLE"])
def test_float_subtypes_read_back_exactly(tmp_path, subtype):
    data = RNG.uniform(-1, 1, 1000)
    if subtype == "FLOAT":
        data = data.astype(np.float32).astype(np.float64)
    path = tmp_path / "x.wav"
    sf.write(path, data, 44100, subtype=subtype)
    np.testing.assert_array_equal(audio.FORMAT.read(path).data, data)


@pytest.mark.parametrize("subtype", ["ULAW", "ALAW"])
def test_companded_subtypes_decode_to_their_codes(tmp_path, subtype):
    data = RNG.uniform(-0.9, 0.9, 1000)
    path = tmp_path / "x.wav"
    sf.write(path, data, 8000, subtype=subtype)
    decoded = audio.FORMAT.read(path).data
    # Companding quantises: each value lands within one code step (at most 1/32 near full scale).
    assert np.abs(decoded - data).max() < 1 / 32
    # Writing the decoded codes again is lossless: they are exactly the file's samples.
    sf.write(path, decoded, 8000, subtype=subtype)
    np.testing.assert_array_equal(audio.FORMAT.read(path).data, decoded)


def test_ogg_vorbis_reads_close_to_the_source(tmp_path):
    t = np.arange(8000) / 8000
    data = 0.5 * np.sin(2 * np.pi * 200 * t)
    path = tmp_path / "x.ogg"
    sf.write(path, data, 8000, format="OGG", subtype="VORBIS")
    tile = audio.FORMAT.read(path)
    assert tile.rate == 8000 and len(tile.data) == len(data)
    assert np.abs(tile.data[1000:7000] - data[1000:7000]).max() < 0.05  # lossy codec


def test_mix_is_the_mean_of_the_channels(tmp_path):
    data = _levels(16, channels=3)
    path = tmp_path / "x.wav"
    sf.write(path, data, 1000, subtype="PCM_16")
    np.testing.assert_allclose(audio.FORMAT.read(path).data, data.mean(axis=1), rtol=0, atol=1e-15)
    np.testing.assert_allclose(audio.FORMAT.read(path, channel="mix").data, data.mean(axis=1))


def test_missing_channel_is_one_sentence(tmp_path):
    path = tmp_path / "x.wav"
    sf.write(path, _levels(16, channels=2), 1000, subtype="PCM_16")
    with pytest.raises(FormatError, match="has 2 channel"):
        audio.FORMAT.read(path, channel=3)
    with pytest.raises(FormatError, match="channel must be"):
        audio.FORMAT.read(path, channel="left")


def test_long_file_is_read_in_blocks_with_progress(tmp_path, monkeypatch):
    """A few minutes at 48 kHz: read in blocks, progress rises to 1, samples exact."""
    monkeypatch.setattr(audio, "BLOCK_FRAMES", 1 << 18)
    n = 48000 * 180
    data = (np.arange(n) % 65536 - 32768) / 32768.0
    path = tmp_path / "long.wav"
    sf.write(path, data, 48000, subtype="PCM_16")
    reads: list[int] = []
    real_read = sf.SoundFile.read

    def counting_read(self, *args, **kwargs):
        out = real_read(self, *args, **kwargs)
        reads.append(len(out))
        return out

    monkeypatch.setattr(sf.SoundFile, "read", counting_read)
    seen: list[float] = []
    tile = audio.FORMAT.read(path, progress=seen.append)
    assert max(reads) <= 1 << 18  # never more than one block at a time
    assert sum(reads) == n
    assert seen == sorted(seen) and seen[-1] == 1.0 and len(seen) == len(reads)
    assert tile.data[12345] == data[12345] and tile.data[-1] == data[-1]


def test_scipy_files_read_or_fail_clearly():
    if not SCIPY_DATA.is_dir():
        pytest.skip("scipy's test data is not installed")
    good = {
        "test-8000Hz-le-3ch-5S-24bit.wav": (8000, 5),
        "test-8000Hz-le-3ch-5S-24bit-rf64.wav": (8000, 5),
        "test-8000Hz-le-1ch-1byte-ulaw.wav": (8000, 9),
        "test-48000Hz-2ch-64bit-float-le-wavex.wav": (48000, 480),
        "test-44100Hz-be-1ch-4bytes.wav": (44100, 4410),
    }
    for name, (rate, n) in good.items():
        tile = audio.FORMAT.read(SCIPY_DATA / name)
        assert (tile.rate, len(tile.data)) == (rate, n)
    with pytest.raises(FormatError, match="truncated"):
        audio.FORMAT.read(SCIPY_DATA / "test-44100Hz-le-1ch-4bytes-early-eof.wav")
    with pytest.raises(FormatError, match="not an audio file"):
        audio.FORMAT.read(SCIPY_DATA / "test-44100Hz-le-1ch-4bytes-early-eof-no-data.wav")
    with pytest.raises(FormatError, match="unimplemented"):
        audio.FORMAT.read(SCIPY_DATA / "test-8000Hz-le-3ch-5S-36bit.wav")


def test_imported_samples_appear_in_the_render_scaled_by_gain(tmp_path):
    data = _levels(16, n=1000)[:, 0]
    path = tmp_path / "x.wav"
    sf.write(path, data, 10000, subtype="PCM_16")
    project, _ = importing.import_file(new_project(), path, at=0.25, gain=0.5)
    drive = mixer.render(project, 0.0, 0.4)["drive"]
    full_scale = 0.18  # the drive kind's full scale: a sample of 1.0 is 0.18 N*m
    np.testing.assert_allclose(drive[2500:3500], 0.5 * full_scale * data, rtol=0, atol=1e-15)
    assert not drive[:2500].any() and not drive[3500:].any()


@pytest.mark.parametrize("subtype", ["PCM_24", "FLOAT", "DOUBLE"])
def test_wav_export_at_a_chosen_rate_and_subtype_imports_back(tmp_path, subtype):
    data = _levels(16, n=1000)[:, 0]
    src = tmp_path / "x.wav"
    sf.write(src, data, 10000, subtype="PCM_16")
    project, _ = importing.import_file(new_project(), src)
    out = tmp_path / "out.wav"
    exporting.export_project(project, out, subtype=subtype)
    assert sf.info(out).subtype == subtype
    back = importing.read_file(out).placements[0].tile
    np.testing.assert_allclose(back.data, data * 0.18, atol=2**-22)
    exporting.export_project(project, out, rate=8000)
    assert sf.info(out).samplerate == 8000


def test_export_picks_a_subtype_each_container_can_hold(tmp_path):
    from timeline import edits
    from timeline.files.exporting import export_project
    from timeline.tiles import generator

    p = edits.new_project(templates=False)
    p, track = edits.add_track(p, "drive")
    p, tile = edits.add_tile(p, generator("sine", 0.1, frequency=100))
    p, _ = edits.add_clip(p, track, tile, 0.0)
    expected = {"wav": "FLOAT", "flac": "PCM_24", "ogg": "VORBIS", "aiff": "FLOAT"}
    for ext, subtype in expected.items():
        export_project(p, tmp_path / f"x.{ext}")
        assert sf.info(str(tmp_path / f"x.{ext}")).subtype == subtype
    data, rate = sf.read(str(tmp_path / "x.flac"))
    assert rate == 10_000 and abs(data.max() - 0.18) < 1e-6  # 24-bit keeps the peak


def test_place_on_a_chosen_track_uses_that_tracks_kind(tmp_path):
    from timeline import edits, render
    from timeline.files.importing import import_file, place, read_file

    path = tmp_path / "tone.wav"
    sf.write(str(path), np.full(100, 0.5), 10_000, subtype="DOUBLE")
    p = edits.new_project(templates=False)
    p, first = edits.add_track(p, "drive")
    p, second = edits.add_track(p, "stiffness")
    p2, clips = place(p, read_file(path), at=0.01, track_id=second)
    assert p2.find_clip(clips[0])[0].id == second
    assert render(p2)["stiffness"][100] == 0.5  # stiffness full scale 1 N*m/rad
    p3, clips = import_file(p, path)  # no track chosen: the first drive track
    assert p3.find_clip(clips[0])[0].id == first
