"""Audio headers that declare more frames than the file holds are refused, never allocated."""

import struct

import numpy as np
import pytest
import soundfile as sf

from importers.audio import FORMAT
from timeline.plugins.file_formats import FormatError

TONE = np.sin(np.arange(1000) / 10) * 0.5


def _flac_declaring(tmp_path, frames: int):
    path = tmp_path / "x.flac"
    sf.write(path, TONE, 8000, subtype="PCM_16")
    data = bytearray(path.read_bytes())
    # STREAMINFO starts at byte 8; its total-samples field is the low 36 bits of bytes 18..25.
    packed = int.from_bytes(data[18:26], "big")
    packed = (packed & ~(2**36 - 1)) | frames
    data[18:26] = packed.to_bytes(8, "big")
    path.write_bytes(bytes(data))
    return path


def test_a_flac_declaring_more_frames_than_a_tile_holds_is_refused(tmp_path):
    path = _flac_declaring(tmp_path, 2**36 - 1)
    with pytest.raises(FormatError, match=r"declares 68719476735 frames, more than one tile"):
        FORMAT.read(path)


def test_a_flac_declaring_a_billion_frames_is_truncated_not_a_memory_error(tmp_path):
    path = _flac_declaring(tmp_path, 10**9)  # 8 GB if allocated up front; the file holds 1000
    with pytest.raises(FormatError, match=r"^x.flac (is truncated|could not be read to the end)"):
        FORMAT.read(path)


def test_an_honest_flac_reads_exactly(tmp_path):
    path = tmp_path / "ok.flac"
    sf.write(path, TONE, 8000, subtype="PCM_24")
    tile = FORMAT.read(path)
    assert tile.rate == 8000 and len(tile.data) == 1000
    assert np.max(np.abs(tile.data - TONE)) < 2**-22


def test_an_aiff_declaring_more_frames_than_it_holds_is_refused(tmp_path):
    path = tmp_path / "x.aiff"
    sf.write(path, TONE, 8000, subtype="PCM_16")
    data = bytearray(path.read_bytes())
    comm = data.find(b"COMM")
    struct.pack_into(">I", data, comm + 10, 2**31 - 1)  # numSampleFrames
    path.write_bytes(bytes(data))
    with pytest.raises(FormatError, match=r"declares 2147483647 frames but it holds 1000"):
        FORMAT.read(path)


@pytest.mark.parametrize("mantissa", [0xC000_0000_0000_0000, 0x8000_0000_0000_0000])  # NaN, inf
def test_an_aiff_whose_rate_is_nan_or_infinite_is_refused_not_read_at_67_mhz(tmp_path, mantissa):
    path = tmp_path / "x.aiff"
    sf.write(path, np.zeros(4), 8000, subtype="PCM_16")
    data = bytearray(path.read_bytes())
    rate = data.find(b"COMM") + 16  # after the chunk header, channels, frames and sample size
    struct.pack_into(">HQ", data, rate, 0x7FFF, mantissa)
    path.write_bytes(bytes(data))
    assert sf.info(path).samplerate == 67_108_864  # what libsndfile makes of it
    with pytest.raises(FormatError, match=r"^x.aiff declares a sample rate that is not a finite"):
        FORMAT.read(path)


def test_an_honest_aiff_keeps_its_rate(tmp_path):
    path = tmp_path / "x.aiff"
    sf.write(path, TONE, 8000, subtype="PCM_16")
    assert FORMAT.read(path).rate == 8000


@pytest.mark.parametrize(
    ("exponent", "mantissa", "declared"),
    [
        (0, 0, "0"),
        (0, 1, "0"),
        (16373, 0x8312_6E97_8D4F_DF3B, "0.001"),
        (0x7FFE, 2**64 - 1, "inf"),
    ],  # fmt: skip
)
def test_an_aiff_rate_libsndfile_cannot_hold_is_refused(tmp_path, exponent, mantissa, declared):
    """0, a denormal and 1e-3 Hz were read as 1 Hz (a 0.1 s sound lasted 100 s), the largest
    finite rate as 67,108,864 Hz, all without a word (found by the hostile campaign)."""
    path = tmp_path / "x.aiff"
    sf.write(path, np.zeros(4), 8000, subtype="PCM_16")
    data = bytearray(path.read_bytes())
    struct.pack_into(">HQ", data, data.find(b"COMM") + 16, exponent, mantissa)
    path.write_bytes(bytes(data))
    with pytest.raises(FormatError, match=rf"^x.aiff declares a sample rate of {declared} Hz, "):
        FORMAT.read(path)


def test_a_header_libsndfile_gives_up_on_is_called_damaged(tmp_path):
    path = tmp_path / "x.aiff"
    sf.write(path, TONE, 8000, subtype="PCM_16")
    path.write_bytes(path.read_bytes()[:30])
    with pytest.raises(FormatError, match=r"^x.aiff is not an audio file that can be read \(its "):
        FORMAT.read(path)
