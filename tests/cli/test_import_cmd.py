"""`haptic-timeline import`: bad input leaves the project file byte for byte; good input renders."""

from __future__ import annotations

import numpy as np
import pytest
import soundfile as sf

from timeline.cli.main import main
from timeline.files import projectfile
from timeline.rendering import mixer

RNG = np.random.default_rng(11)


@pytest.fixture
def project_file(tmp_path):
    """A project made by the CLI from a real WAV, with its bytes."""
    wav = tmp_path / "first.wav"
    sf.write(wav, RNG.uniform(-1, 1, 500), 10000, subtype="DOUBLE")
    path = tmp_path / "design.htl"
    assert main(["import", str(wav), "--into", str(path)]) == 0
    return path


def _bad_files(tmp_path):
    good = tmp_path / "good.wav"
    sf.write(good, RNG.uniform(-1, 1, 2000), 8000, subtype="PCM_16")
    truncated = tmp_path / "truncated.wav"
    truncated.write_bytes(good.read_bytes()[:2000])
    header_only = tmp_path / "nodata.wav"
    sf.write(header_only, np.zeros((0, 1)), 8000, subtype="PCM_16")
    text = tmp_path / "notes.wav"
    text.write_text("this is not audio\n" * 20)
    nan = tmp_path / "nan.wav"
    sf.write(nan, np.array([0.0, np.nan, 0.5]), 8000, subtype="DOUBLE")
    inf = tmp_path / "inf.flac.wav"
    sf.write(inf, np.array([0.0, np.inf]), 8000, subtype="FLOAT")
    empty = tmp_path / "empty.wav"
    empty.write_bytes(b"")
    folder = tmp_path / "folder.wav"
    folder.mkdir()
    return {
        truncated: "truncated",
        header_only: "holds no audio samples",
        text: "not an audio file",
        nan: "not a finite number",
        inf: "not a finite number",
        empty: "is empty",
        tmp_path / "missing.wav": "does not exist",
        folder: "is a directory",
        tmp_path / "x.xyz": "does not exist",
    }


def test_bad_input_is_one_sentence_and_leaves_the_project_unchanged(tmp_path, project_file, capsys):
    before = project_file.read_bytes()
    capsys.readouterr()
    for path, message in _bad_files(tmp_path).items():
        assert main(["import", str(path), "--into", str(project_file)]) == 1, path.name
        err = capsys.readouterr().err.strip()
        assert message in err, (path.name, err)
        assert err.count("\n") == 0 and "Traceback" not in err
        assert project_file.read_bytes() == before, path.name


def test_bad_options_leave_the_project_unchanged(tmp_path, project_file, capsys):
    before = project_file.read_bytes()
    wav = tmp_path / "stereo.wav"
    sf.write(wav, RNG.uniform(-1, 1, (100, 2)), 8000, subtype="PCM_16")
    cases = [
        (["--channel", "3"], "no channel 3"),
        (["--column", "drive"], "column option does not apply"),
        (["--track", "spin"], "unknown track"),
    ]
    for extra, message in cases:
        assert main(["import", str(wav), "--into", str(project_file), *extra]) == 1
        assert message in capsys.readouterr().err
        assert project_file.read_bytes() == before


def test_import_places_the_samples_at_the_time_with_the_gain(tmp_path):
    data = RNG.integers(-32768, 32768, 1000) / 32768
    wav = tmp_path / "tap.wav"
    sf.write(wav, np.column_stack([data, -data]), 10000, subtype="PCM_16")
    htl = tmp_path / "new.htl"
    args = ["import", str(wav), "--into", str(htl), "--at", "0.5", "--gain", "2", "--channel", "2"]
    assert main(args) == 0
    assert main(["import", str(wav), "--into", str(htl), "--track", "stiffness"]) == 0
    project = projectfile.load(htl)
    assert project.axis == "time" and project.rate == 10000.0
    assert [t.kind for t in project.tracks] == ["drive", "stiffness"]
    layers = mixer.render(project, 0.0, 0.7)
    np.testing.assert_allclose(layers["drive"][5000:6000], -data * 2 * 0.18, atol=1e-15)
    assert not layers["drive"][:5000].any()
    assert not layers["stiffness"].any()  # the mix of a channel and its negation is silence


def test_second_import_goes_on_the_first_track_of_the_kind(tmp_path, project_file):
    wav = tmp_path / "more.wav"
    sf.write(wav, RNG.uniform(-1, 1, 100), 10000, subtype="DOUBLE")
    assert main(["import", str(wav), "--into", str(project_file), "--at", "1"]) == 0
    project = projectfile.load(project_file)
    assert len(project.tracks) == 1 and len(project.tracks[0].clips) == 2


def test_csv_import_with_column_and_rate(tmp_path):
    csv = tmp_path / "scope.csv"
    csv.write_text("a,b\n0.1,0.2\n0.3,0.4\n")
    htl = tmp_path / "p.htl"
    assert main(["import", str(csv), "--into", str(htl), "--column", "b", "--rate", "100"]) == 0
    project = projectfile.load(htl)
    tile = project.tile(project.tracks[0].clips[0].tile_id)
    assert tile.rate == 100 and list(tile.data) == [0.2, 0.4]


def test_import_prints_each_reader_note_on_its_own_line(tmp_path, capsys):
    import json

    design = {
        "version": {"major": 1, "minor": 0},
        "signals": {
            "continuous": {
                "envelopes": {
                    "amplitude": [
                        {
                            "time": 0.0,
                            "amplitude": 0.5,
                            "emphasis": {"amplitude": 0.2, "frequency": 0.5},
                        },
                        {"time": 0.4, "amplitude": 0.5},
                    ]
                }
            }
        },
    }
    src = tmp_path / "weak.haptic"
    src.write_text(json.dumps(design))
    assert main(["import", str(src), "--into", str(tmp_path / "p.htl")]) == 0
    lines = capsys.readouterr().err.splitlines()
    notes = [line for line in lines if line.startswith("note: ")]
    assert len(notes) == 2
    assert "no frequency envelope: frequency 0.5 assumed" in notes[0]
    assert "emphasis at 0 s (0.2) is weaker than its breakpoint (0.5)" in notes[1]
    assert lines[0].startswith("imported ") and len(lines) == 3
