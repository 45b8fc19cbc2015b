"""The render and info verbs, and one-sentence errors with a non-zero exit."""

import json
from pathlib import Path

import numpy as np
import pytest
import soundfile

from timeline.cli.main import main

PROJECTS = Path(__file__).resolve().parents[2] / "projects"


def test_render_csv_has_the_axis_then_one_column_per_layer(tmp_path, capsys):
    out = tmp_path / "r.csv"
    assert main(["render", str(PROJECTS / "rising_resistance.htl"), "-o", str(out)]) == 0
    header = out.read_text().splitlines()[0]
    assert header == "time,stiffness,damping"
    table = np.loadtxt(out, delimiter=",", skiprows=1)
    assert table.shape == (20_000, 3)
    assert table[10_000, 0] == 1.0
    # ramp half way, gain 0.4 (below the delayed passivity bound, build_examples.py), 1 N*m/rad
    assert table[10_000, 1] == pytest.approx(0.4 * 0.5)
    assert "20000 samples" in capsys.readouterr().err


def test_render_position_project_uses_an_angle_column(tmp_path):
    out = tmp_path / "fan.csv"
    assert main(["render", str(PROJECTS / "fan_knob.htl"), "-o", str(out), "--rate", "100"]) == 0
    assert out.read_text().splitlines()[0] == "angle_deg,torque,damping,mass"  # issue 22.1


def test_render_npz_and_wav_with_range_rate_and_tracks(tmp_path):
    src = str(PROJECTS / "rising_resistance.htl")
    assert (
        main(
            [
                "render",
                src,
                "-o",
                str(tmp_path / "r.npz"),
                "--start",
                "0.5",
                "--stop",
                "1",
                "--rate",
                "1000",
                "--tracks",
                "Spring",
                "--quality",
                "exact",
            ]
        )
        == 0
    )
    data = np.load(tmp_path / "r.npz")
    assert sorted(data.files) == ["rate", "stiffness", "time", "units"]  # issue 22.2
    assert len(data["time"]) == 500 and data["time"][0] == 0.5
    np.testing.assert_allclose(data["stiffness"], 0.4 * data["time"] / 2, rtol=1e-12)  # gain 0.4
    assert (
        main(["render", str(PROJECTS / "notification_buzz.htl"), "-o", str(tmp_path / "b.wav")])
        == 0
    )
    wav, rate = soundfile.read(tmp_path / "b.wav")
    assert rate == 10_000 and len(wav) == 5000 and np.abs(wav).max() > 0.1


def test_info_json(capsys):
    assert main(["info", str(PROJECTS / "notification_buzz.htl"), "--json"]) == 0
    info = json.loads(capsys.readouterr().out)
    assert info["layers"] == ["drive"] and info["variants"] == ["A", "B: stronger tap"]
    assert info["duration"] == pytest.approx(0.5)


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["render", "missing.htl", "-o", "x.csv"], "does not exist"),
        (["render", "{fan}", "-o", "x.wav"], "samples per radian, and audio files need"),
        (["render", "{fan}", "-o", "x.xlsx"], "xlsx"),
        (["render", "{fan}", "-o", "x.csv", "--tracks", "Nope"], "no track named 'Nope'"),
        (["render", "{fan}", "-o", "x.csv", "--start", "3", "--stop", "1"], "stops"),
        (["info", "{folder}"], "is a folder"),
    ],
)
def test_user_mistakes_print_one_sentence_and_exit_non_zero(
    argv, message, capsys, tmp_path, monkeypatch
):
    monkeypatch.chdir(tmp_path)
    argv = [a.format(fan=PROJECTS / "fan_knob.htl", folder=tmp_path) for a in argv]
    assert main(argv) == 1
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1 and "Traceback" not in err


def test_bad_numbers_are_argparse_errors(capsys):
    with pytest.raises(SystemExit) as info:
        main(["render", "x.htl", "-o", "y.csv", "--rate", "fast"])
    assert info.value.code == 2 and "'fast' is not a number" in capsys.readouterr().err
