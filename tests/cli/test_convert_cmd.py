"""`haptic-timeline convert`: a sound to .haptic, .ahap and a .htl project that keeps the sound."""

from __future__ import annotations

import json
import tracemalloc
from pathlib import Path

import numpy as np
import pytest
import soundfile as sf

from tests.analysis.conftest import tone_bursts
from timeline.analysis import AnalysisSettings
from timeline.analysis.source import analyse_file
from timeline.cli.main import main
from timeline.edits.vibration import design_of
from timeline.files import projectfile
from timeline.files.convert import design_of_analysis, sound_to_project
from timeline.rendering.source_sound import render_sound

RATE = 44_100
ONSETS = [0.1, 0.45, 0.8]


@pytest.fixture
def bursts(tmp_path: Path) -> Path:
    path = tmp_path / "bursts.wav"
    sf.write(path, tone_bursts(ONSETS, 150.0, 1.2, rate=RATE), RATE, subtype="FLOAT")
    return path


def test_haptic_file_holds_the_analysis(tmp_path: Path, bursts: Path) -> None:
    out = tmp_path / "bursts.haptic"
    assert main(["convert", str(bursts), "-o", str(out), "--sensitivity", "100"]) == 0
    analysis = analyse_file(bursts, AnalysisSettings(sensitivity=100))
    envelopes = json.loads(out.read_text())["signals"]["continuous"]["envelopes"]
    written = np.array([(b["time"], b["amplitude"]) for b in envelopes["amplitude"]])
    np.testing.assert_allclose(written, analysis.amplitude, atol=1e-6)
    emphasis = [b["time"] for b in envelopes["amplitude"] if "emphasis" in b]
    np.testing.assert_allclose(emphasis, ONSETS, atol=0.005)


def test_ahap_file_has_the_hits_as_transients(tmp_path: Path, bursts: Path) -> None:
    out = tmp_path / "bursts.ahap"
    assert main(["convert", str(bursts), "-o", str(out), "--sensitivity", "100"]) == 0
    events = [p["Event"] for p in json.loads(out.read_text())["Pattern"] if "Event" in p]
    transients = [e["Time"] for e in events if e["EventType"] == "HapticTransient"]
    np.testing.assert_allclose(transients, ONSETS, atol=0.005)


def test_project_keeps_the_sound_and_an_editable_design(tmp_path: Path, bursts: Path) -> None:
    out = tmp_path / "bursts.htl"
    assert main(["convert", str(bursts), "-o", str(out), "--gain", "0"]) == 0  # unstaged
    project = projectfile.load(out)
    assert sorted(t.kind for t in project.tracks) == ["audio", "drive", "drive"]
    sound, _ = sf.read(bursts)
    np.testing.assert_allclose(render_sound(project, 0.0, 1.2, RATE), sound, atol=1e-6)
    expected = design_of_analysis(analyse_file(bursts))
    assert design_of(project) == expected  # unedited: the analysis, breakpoint for breakpoint
    # each emphasis is a clip of its own on the Emphasis track, under the envelopes' track
    accents = next(t for t in project.tracks if t.name == "Emphasis")
    assert [c.start for c in accents.clips] == [e.time for e in expected.emphasis]
    assert len(expected.emphasis) == 3  # the three equal bursts, at 50 % sensitivity


def test_sound_lands_where_the_designer_drops_it(bursts: Path) -> None:
    first = sound_to_project(bursts)
    again = sound_to_project(bursts, project=first, at=2.0, keep_sound=False)
    drive = [t for t in again.tracks if t.kind == "drive"]
    assert [t.name for t in drive] == ["Drive 1", "Emphasis"]  # the second reuses both
    assert [c.start for c in drive[0].clips] == [0.0, 2.0]
    accents = [c.start for c in drive[1].clips]
    assert accents == [*accents[:3], *(a + 2.0 for a in accents[:3])]


def test_bad_inputs_are_one_sentence(tmp_path: Path, bursts: Path, capsys) -> None:
    text = tmp_path / "notes.wav"
    text.write_text("not a sound")
    assert main(["convert", str(text), "-o", str(tmp_path / "x.haptic")]) == 1
    err = capsys.readouterr().err.strip()
    assert err.startswith("haptic-timeline: notes.wav is not a sound file") and "\n" not in err
    assert main(["convert", str(bursts), "-o", str(tmp_path / "x.haptic"), "--fft-size", "1000"])
    err = capsys.readouterr().err.strip()
    assert "fft_size must be a power of two" in err and "\n" not in err
    assert not (tmp_path / "x.haptic").exists()


def test_silence_converts_to_a_flat_design(tmp_path: Path) -> None:
    path = tmp_path / "silence.wav"
    sf.write(path, np.zeros(4410), RATE)
    out = tmp_path / "silence.haptic"
    assert main(["convert", str(path), "-o", str(out)]) == 0
    amplitude = json.loads(out.read_text())["signals"]["continuous"]["envelopes"]["amplitude"]
    assert all(b["amplitude"] == 0 for b in amplitude) and amplitude[-1]["time"] == 0.1


def _peak_memory(path: Path, rate: int, minutes: int):
    block = tone_bursts([0.05], 300.0, 1.0, rate=rate).astype(np.float32)
    with sf.SoundFile(path, "w", rate, 1, "PCM_16") as f:
        for _ in range(60 * minutes):
            f.write(block)
    tracemalloc.start()
    analysis = analyse_file(path, AnalysisSettings(sensitivity=100))
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    return peak, analysis


def test_long_sound_is_analysed_in_bounded_memory(tmp_path: Path) -> None:
    rate = 8000
    short, _ = _peak_memory(tmp_path / "one.wav", rate, 1)
    peak, analysis = _peak_memory(tmp_path / "four.wav", rate, 4)
    # four times the sound, the same working memory: a block's spectra (about 16 MB)
    assert peak < 1.25 * short and peak < 32 * 2**20
    assert len(analysis.emphasis) == 240  # one hit a second, every second
    assert analysis.duration == pytest.approx(240.0)


@pytest.mark.slow
def test_two_hour_sound(tmp_path: Path, request, capsys) -> None:
    if "slow" not in (request.config.option.markexpr or ""):
        pytest.skip("slow: run with -m slow")
    rate = 8000
    path = tmp_path / "two_hours.wav"
    block = tone_bursts([0.05], 300.0, 1.0, rate=rate).astype(np.float32)
    with sf.SoundFile(path, "w", rate, 1, "PCM_16") as f:
        for _ in range(2 * 3600):
            f.write(block)
    out = tmp_path / "two_hours.haptic"
    assert main(["convert", str(path), "-o", str(out)]) == 0
    amplitude = json.loads(out.read_text())["signals"]["continuous"]["envelopes"]["amplitude"]
    assert amplitude[-1]["time"] == pytest.approx(7200.0)
    assert main(["convert", str(path), "-o", str(tmp_path / "two_hours.htl")]) == 1
    assert "keeps sounds up to 60 minutes" in capsys.readouterr().err


def test_a_project_refuses_a_sound_too_long_to_keep(
    tmp_path: Path, bursts: Path, monkeypatch, capsys
):
    import timeline.files.convert

    monkeypatch.setattr(timeline.files.convert, "MAX_SOUND_SECONDS", 1.0)
    out = tmp_path / "long.htl"
    assert main(["convert", str(bursts), "-o", str(out)]) == 1
    err = capsys.readouterr().err.strip()
    assert "keeps sounds up to 0 minutes (convert it to .haptic or .ahap instead)" in err
    assert not out.exists()
    assert main(["convert", str(bursts), "-o", str(tmp_path / "long.haptic")]) == 0
