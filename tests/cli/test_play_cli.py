"""`haptic-timeline play` and `haptic-timeline devices` end to end."""

from __future__ import annotations

import csv
from pathlib import Path

from timeline.cli.main import main

PROJECTS = Path(__file__).resolve().parents[2] / "projects"


def test_play_writes_summary_csv_and_plot(tmp_path, capsys) -> None:
    out, png = tmp_path / "t.csv", tmp_path / "t.png"
    args = [str(PROJECTS / "rising_resistance.htl"), "--hand", "turn:45", "-o", str(out)]
    assert main(["play", *args, "--plot", str(png), "--duration", "0.5"]) == 0
    text = capsys.readouterr().out
    assert "peak torque" in text and "energy injected" in text and "flag" in text
    rows = list(csv.reader(out.open()))
    assert rows[0] == ["time", "angle", "velocity", "torque", "stiffness", "damping"]
    assert len(rows) == 5001 and float(rows[-1][0]) == 0.4999
    assert png.stat().st_size > 10_000 and png.read_bytes()[:4] == b"\x89PNG"


def test_play_position_project_names_the_torque_layer_apart(tmp_path) -> None:
    out = tmp_path / "fan.csv"
    assert main(["play", str(PROJECTS / "fan_knob.htl"), "--duration", "0.2", "-o", str(out)]) == 0
    header = out.open().readline().strip().split(",")
    assert header == ["time", "angle", "velocity", "torque", "torque_layer", "damping", "mass"]


def test_user_mistakes_are_one_sentence(tmp_path, capsys) -> None:
    project = str(PROJECTS / "fan_knob.htl")
    for extra in (["--hand", "spin"], ["--device", "nosuch"], ["--duration", "-1"]):
        assert main(["play", project, *extra]) == 1
        err = capsys.readouterr().err.strip().splitlines()
        assert err[-1].startswith("haptic-timeline: ") and "Traceback" not in "".join(err)


def test_devices_lists_the_simulated_knob(capsys) -> None:
    assert main(["devices"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert any(line.startswith("sim: simulated knob") for line in lines)


def test_play_with_a_named_hand_settles_where_its_grip_says(tmp_path, capsys) -> None:
    """18 mNm held by the grasp hand (0.054 N*m/rad) rests near 0.333 rad; the default grip
    (1 N*m/rad) near 0.018 rad; Coulomb friction (1 mNm) leaves a band of 1 mNm / K around it."""
    from timeline import edits, generator, save

    p = edits.new_project("time")
    p, drive = edits.add_track(p, "drive", "drive")
    p, level = edits.add_tile(p, generator("constant", 3.0, "level", value=1.0))
    p, _ = edits.add_clip(p, drive, level, 0.0, gain=0.1)  # 0.1 x 180 mNm
    project = tmp_path / "step.htl"
    save(p, project)
    rest = {}
    for hand in ("grasp", "hold"):
        out = tmp_path / f"{hand}.csv"
        assert main(["play", str(project), "--hand", hand, "-o", str(out)]) == 0
        assert f"with hand {hand}" in capsys.readouterr().out
        rows = list(csv.reader(out.open()))
        rest[hand] = float(rows[-1][1])
    assert abs(rest["grasp"] - 0.018 / 0.054) < 1e-3 / 0.054
    assert abs(rest["hold"] - 0.018 / 1.0) < 1e-3 / 1.0
