"""`haptic-timeline export`: every written format imports back with `import`."""

from __future__ import annotations

import numpy as np
import pytest
import soundfile as sf

from timeline.cli.main import main
from timeline.files import projectfile


@pytest.fixture
def design(tmp_path):
    t = np.arange(3000) / 10000
    wav = tmp_path / "buzz.wav"
    sf.write(wav, 0.5 * np.sin(2 * np.pi * 170 * t), 10000, subtype="DOUBLE")
    htl = tmp_path / "design.htl"
    assert main(["import", str(wav), "--into", str(htl)]) == 0
    return htl


@pytest.mark.parametrize("ext", [".ahap", ".haptic", ".otio", ".mat", ".csv", ".txt", ".wav"])
def test_export_then_import_back(tmp_path, design, ext):
    out = tmp_path / f"out{ext}"
    assert main(["export", str(design), "-o", str(out)]) == 0
    again = tmp_path / "again.htl"
    assert main(["import", str(out), "--into", str(again)]) == 0
    project = projectfile.load(again)
    clips = [c for t in project.tracks for c in t.clips]
    assert clips and abs(max(c.end for c in clips) - 0.3) < 0.002


def test_export_rate_is_used(tmp_path, design):
    out = tmp_path / "out.wav"
    assert main(["export", str(design), "-o", str(out), "--rate", "8000"]) == 0
    assert sf.info(out).samplerate == 8000 and sf.info(out).frames == 2400


def test_unknown_extension_and_empty_project_are_one_sentence(tmp_path, design, capsys):
    assert main(["export", str(design), "-o", str(tmp_path / "x.doc")]) == 1
    assert "no format writes .doc files" in capsys.readouterr().err
    empty = tmp_path / "empty.htl"
    from timeline.edits import new_project

    projectfile.save(new_project(), empty)
    assert main(["export", str(empty), "-o", str(tmp_path / "x.ahap")]) == 1
    assert "no clips to export" in capsys.readouterr().err
    assert not (tmp_path / "x.ahap").exists()
