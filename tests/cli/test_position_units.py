"""Every verb on a position project speaks degrees: what a person types and what they read.

The fan knob's axis is radians inside (its files too); on the command line its clips sit at 0-20,
20-260 and 260-280 deg and its settings Off/Lo/Med/Hi at 50/110/170/230 deg.
"""

import json
import math
import shutil
from pathlib import Path

import numpy as np
import pytest
import soundfile

from timeline import edits
from timeline.cli.main import main
from timeline.edits import tile_shape
from timeline.files import projectfile
from timeline.rendering import playback

FAN = Path(__file__).resolve().parents[2] / "projects" / "fan_knob.htl"


@pytest.fixture
def fan(tmp_path) -> Path:
    path = tmp_path / "fan.htl"
    shutil.copy(FAN, path)
    return path


@pytest.fixture
def knock(tmp_path) -> Path:
    """Half a second of a 50 Hz tone at 1 kHz: a recording, in seconds."""
    path = tmp_path / "knock.wav"
    soundfile.write(path, 0.5 * np.sin(2 * np.pi * 50 * np.arange(500) / 1000), 1000)
    return path


def _clips(path: Path, track: str = "torque") -> list:
    project = projectfile.load(path)
    return [c for t in project.tracks if t.kind == track for c in t.clips]


def test_info_prints_extent_clips_and_markers_in_degrees(capsys):
    assert main(["info", str(FAN)]) == 0
    out = capsys.readouterr().out
    assert "100 samples/deg (5729.58 samples/rad), duration 280 deg" in out
    assert "c22: four detents 20 to 260 deg (240 deg)" in out
    assert "markers: Off 50 deg, Lo 110 deg, Med 170 deg, Hi 230 deg" in out
    assert " rad" not in out.replace("samples/rad", "").replace("N*m*s/rad", "")
    assert main(["info", str(FAN), "--json"]) == 0
    info = json.loads(capsys.readouterr().out)
    assert (info["unit"], info["rate_unit"]) == ("deg", "samples/rad")
    assert info["duration"] == pytest.approx(280)
    detents = info["tracks"][0]["clips"][1]
    assert (detents["start"], detents["length"]) == (pytest.approx(20), pytest.approx(240))
    assert [m["at"] for m in info["markers"]] == pytest.approx([50, 110, 170, 230])


def test_render_start_and_stop_are_degrees(tmp_path, capsys):
    out = tmp_path / "fan.csv"
    args = ["render", str(FAN), "-o", str(out), "--start", "50", "--stop", "100", "--rate", "1/deg"]
    assert main(args) == 0
    assert "50 samples, 50 deg to 100 deg at 1/deg" in capsys.readouterr().err
    angles = np.loadtxt(out, delimiter=",", skiprows=1, comments="#")[:, 0]  # angle_deg
    assert len(angles) == 50 and angles[0] == pytest.approx(50.0)
    assert main([*args[:4], "--start", "0.8727rad", "--stop", "1.7453rad", "--rate", "1/deg"]) == 0
    assert "50 samples, 50.002 deg to 99.9983 deg" in capsys.readouterr().err


def test_render_refuses_seconds_on_an_angle_axis(tmp_path, capsys):
    assert main(["render", str(FAN), "-o", str(tmp_path / "x.csv"), "--stop", "0.5s"]) == 1
    err = capsys.readouterr().err
    assert "--stop 0.5s is a time, but the project's axis is an angle: give degrees" in err
    assert err.count("\n") == 1


def test_import_at_is_degrees_and_says_how_seconds_became_degrees(fan, knock, capsys):
    assert main(["import", str(knock), "--into", str(fan), "--track", "torque", "--at", "90"]) == 0
    err = capsys.readouterr().err
    assert "1 clip(s) at 90 deg" in err
    assert (
        "note: knock.wav is in seconds: one radian per second made its 0.5 s 28.6479 deg of the "
        "knob's angle (1 s = 57.2958 deg); --length DEG gives it another span"
    ) in err
    clip = next(c for c in _clips(fan) if c.start == pytest.approx(math.pi / 2))
    assert clip.duration == pytest.approx(0.5)  # one radian per second
    assert projectfile.load(fan).duration == pytest.approx(math.radians(280))  # not 91 rad


def test_import_length_spreads_a_recording_over_degrees(fan, knock, capsys):
    args = ["import", str(knock), "--into", str(fan), "--track", "torque"]
    assert main([*args, "--at", "1.2rad", "--length", "30"]) == 0
    assert "--length made its 0.5 s 30 deg of the knob's angle (1 s = 60 deg)" in (
        capsys.readouterr().err
    )
    clip = next(c for c in _clips(fan) if c.start == pytest.approx(1.2))
    assert clip.duration == pytest.approx(math.radians(30)) and clip.stretch == pytest.approx(
        math.radians(30) / 0.5
    )
    assert main([*args, "--at", "0.25s"]) == 1
    assert "--at 0.25s is a time, but the project's axis is an angle" in capsys.readouterr().err


def test_import_at_and_length_stay_seconds_on_a_time_project(tmp_path, knock, capsys):
    project = tmp_path / "new.htl"
    args = ["import", str(knock), "--into", str(project), "--at", "0.25", "--length", "500ms"]
    assert main(args) == 0
    assert "note:" not in capsys.readouterr().err  # seconds into seconds: nothing to say
    (clip,) = _clips(project, "drive")
    assert (clip.start, clip.duration) == (0.25, pytest.approx(0.5))
    assert main(["import", str(knock), "--into", str(project), "--at", "90deg"]) == 1
    assert "--at 90deg is an angle, but the project's axis is a time" in capsys.readouterr().err


def test_play_origin_is_degrees(monkeypatch, capsys):
    seen = []
    prepare = playback.prepare

    def spy(project, info, duration, hand, quality, origin):
        seen.append(origin)
        return prepare(project, info, duration, hand, quality, origin)

    monkeypatch.setattr(playback, "prepare", spy)
    assert main(["play", str(FAN), "--origin", "100", "--duration", "0.01"]) == 0
    assert main(["play", str(FAN), "--origin", "1.5rad", "--duration", "10ms"]) == 0
    assert seen == [pytest.approx(math.radians(100)), 1.5]


def test_export_rate_per_degree_and_range_tile_names(tmp_path):
    out = tmp_path / "fan.json"
    assert main(["export", str(FAN), "-o", str(out), "--rate", "1/deg"]) == 0
    assert json.loads(out.read_text())["count"] == 281  # one entry per degree, 0 to 280
    project = projectfile.load(FAN)
    detents = next(c.tile_id for t in project.tracks for c in t.clips if c.id == "c22")
    project, tile = tile_shape.range_to_palette(
        project, detents, math.radians(20), math.radians(200)
    )
    assert project.tile(tile).name == "four detents 20-200 deg"


def test_check_gives_spans_in_degrees(tmp_path, capsys):
    project = projectfile.load(FAN)
    walls = next(t.id for t in project.tracks if t.kind == "torque")
    hot = tmp_path / "hot.htl"
    projectfile.save(edits.set_track(project, walls, gain=3.0), hot)  # the walls saturate
    assert main(["check", str(hot)]) == 3
    assert "maximum output at 0.0 to 11.7 deg (0.432 N*m" in capsys.readouterr().out
    assert main(["check", str(hot), "--json"]) == 3
    first = json.loads(capsys.readouterr().out)["findings"][0]
    assert (first["start"], first["stop"], first["span_unit"]) == (0.0, 11.67, "deg")
