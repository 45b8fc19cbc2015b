"""Sound files analysed in blocks: formats, channels, and files that are not sound."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import soundfile as sf

from tests.analysis.conftest import RATE, tone_bursts
from timeline.analysis import analyse
from timeline.analysis.source import analyse_file
from timeline.errors import AnalysisError


def test_stereo_file_is_its_channels_mixed(tmp_path: Path) -> None:
    left = tone_bursts([0.05, 0.3], 150.0, 0.6)
    stereo = np.column_stack([left, 0.5 * left]).astype(np.float32)
    path = tmp_path / "burst.flac"
    sf.write(path, stereo, RATE, subtype="PCM_24")
    from_file = analyse_file(path)
    in_memory = analyse(sf.read(path)[0], RATE)
    np.testing.assert_allclose(from_file.amplitude, in_memory.amplitude, atol=1e-5)
    np.testing.assert_allclose(from_file.emphasis, in_memory.emphasis, atol=1e-5)
    assert from_file.rate == RATE and from_file.duration == pytest.approx(0.6)


def test_not_a_sound_file_is_one_sentence(tmp_path: Path) -> None:
    path = tmp_path / "notes.wav"
    path.write_text("these are notes, not sound\n")
    with pytest.raises(AnalysisError, match=r"^notes.wav is not a sound file that can be read"):
        analyse_file(path)
    with pytest.raises(AnalysisError, match="there is no sound file"):
        analyse_file(tmp_path / "missing.wav")


def test_empty_sound_file(tmp_path: Path) -> None:
    path = tmp_path / "empty.wav"
    sf.write(path, np.zeros(0), RATE)
    with pytest.raises(AnalysisError, match="holds no audio samples"):
        analyse_file(path)


def test_a_file_read_once_or_twice_gives_the_same_design(tmp_path: Path, monkeypatch) -> None:
    from timeline.analysis import source

    monkeypatch.setattr(source, "BLOCK_FRAMES", 5000)  # several blocks and a short last one
    stereo = np.column_stack([tone_bursts([0.05, 0.2], 150.0, 0.3)] * 2).astype(np.float32)
    path = tmp_path / "burst.wav"
    sf.write(path, stereo, RATE, subtype="FLOAT")
    held = analyse_file(path)
    monkeypatch.setattr(source, "HELD_FRAMES", 0)  # read twice, as a long file is
    twice = analyse_file(path)
    for name in ("amplitude", "frequency", "emphasis"):
        np.testing.assert_array_equal(getattr(held, name), getattr(twice, name))
    assert len(held.emphasis) == 2
