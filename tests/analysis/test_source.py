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
