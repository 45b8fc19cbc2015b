"""`haptic-timeline check`: quiet on the examples, every kind of finding on designs built for it."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from timeline import edits, generator, save
from timeline.cli import main as cli

EXAMPLES = Path(__file__).resolve().parents[2] / "projects"


@pytest.mark.parametrize("name", ["fan_knob", "notification_buzz", "rising_resistance"])
def test_the_examples_are_quiet(name: str, capsys) -> None:
    assert cli.main(["check", str(EXAMPLES / f"{name}.htl"), "--json"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert report["findings"] == []
    assert report["limits"]["damping"] == pytest.approx(0.2002, rel=1e-3)
    assert report["limits"]["mass_high"] == pytest.approx(2.876e-5, rel=1e-3)  # Kalman observer


@pytest.mark.parametrize("name", ["fan_knob", "notification_buzz", "rising_resistance"])
@pytest.mark.parametrize(
    "options",
    [["--device-option", "delay=1"], ["--device-option", "estimator=filter"],
     ["--device", "usb", "--device-option", "emulate=true"], ["--hand", "grasp-turn:45"]],
)  # fmt: skip
def test_the_examples_are_quiet_on_every_loop(name: str, options: list[str], capsys) -> None:
    assert cli.main(["check", str(EXAMPLES / f"{name}.htl"), "--json", *options]) == 0
    assert json.loads(capsys.readouterr().out)["findings"] == []


def _crossing_everything():
    """One time project whose parts each cross one limit, in its own stretch of time."""
    p = edits.new_project("time")
    p, drive = edits.add_track(p, "drive", "drive")
    p, spring = edits.add_track(p, "stiffness", "spring")
    p, damper = edits.add_track(p, "damping", "damper")
    p, mass = edits.add_track(p, "mass", "mass")
    p, level = edits.add_tile(p, generator("constant", 0.1, "level", value=1.0))
    p, faint = edits.add_tile(p, generator("sine", 0.1, "faint", frequency=250.0))
    p, low = edits.add_tile(p, generator("sine", 0.2, "low", frequency=90.0))
    p, _ = edits.add_clip(p, drive, level, 0.0, gain=1.2)  # 216 mNm: saturates
    p, _ = edits.add_clip(p, drive, level, 0.105, gain=0.5)  # 5 ms after: too short a gap
    p, _ = edits.add_clip(p, drive, level, 0.3, gain=0.5 * 10 ** (1 / 20))  # 1 dB louder
    p, _ = edits.add_clip(p, drive, faint, 0.5, gain=1e-5)  # 1.8 uNm at 250 Hz
    p, _ = edits.add_clip(p, drive, low, 0.7, gain=0.5)  # 90 Hz, outside an LRA at 175 Hz
    p, _ = edits.add_clip(p, spring, level, 1.0, gain=3.0)  # 3 N*m/rad > 2
    p, _ = edits.add_clip(p, damper, level, 1.2, gain=3000.0)  # 0.3 N*m*s/rad > 0.2
    p, _ = edits.add_clip(p, damper, level, 1.4, gain=-0.1)
    p, _ = edits.add_clip(p, mass, level, 1.6, gain=30.0)  # 3e-4 kg*m^2 > 2.88e-5
    p, _ = edits.add_clip(p, mass, level, 1.8, gain=-2.0)  # J + m < 0
    p = edits.save_variant(p, "A")
    return edits.save_variant(p, "A again")


def test_check_json_names_every_kind_of_finding(tmp_path: Path, capsys) -> None:
    path = tmp_path / "everything.htl"
    save(_crossing_everything(), path)
    args = ["check", str(path), "--json", "--actuator", "lra-175", "--device-option", "slew=100"]
    assert cli.main(args) == 3
    report = json.loads(capsys.readouterr().out)
    kinds = {f["kind"] for f in report["findings"]}
    assert kinds == {
        "torque-saturation",
        "gap-too-short",
        "sub-jnd",
        "below-detection",
        "outside-actuator-band",
        "stiffness-limit",
        "damping-limit",
        "negative-damping",
        "mass-limit",
        "mass-cancels-inertia",
        "slew-limit",
    }
    for f in report["findings"]:
        assert f["what"] and f["advice"] and f["unit"]
        assert f["start"] < f["stop"]
    by_kind = {f["kind"]: f for f in report["findings"]}
    assert by_kind["torque-saturation"]["value"] == pytest.approx(0.216)
    assert (by_kind["stiffness-limit"]["start"], by_kind["stiffness-limit"]["stop"]) == (
        pytest.approx(1.0),
        pytest.approx(1.1),
    )


def test_check_text_and_bad_actuator(tmp_path: Path, capsys) -> None:
    path = tmp_path / "everything.htl"
    save(_crossing_everything(), path)
    assert cli.main(["check", str(path)]) == 3
    out = capsys.readouterr().out
    assert "stiffness-limit: stiffness above" in out and "1.000 to 1.100 s" in out
    assert cli.main(["check", str(path), "--actuator", "piezo"]) == 1
    err = capsys.readouterr().err
    assert err.startswith("haptic-timeline: unknown actuator 'piezo'") and err.count("\n") == 1


def test_check_plot_draws_rendered_against_designed(tmp_path: Path, capsys) -> None:
    png = tmp_path / "rendered.png"
    args = ["check", str(EXAMPLES / "fan_knob.htl"), "--hand", "turn:90", "--plot", str(png)]
    assert cli.main(args) == 0
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 20_000
    assert "plot ->" in capsys.readouterr().err


def test_check_hand_sets_what_the_knob_makes_felt(tmp_path: Path, capsys) -> None:
    # 0.5 mNm at 250 Hz: a pinch (no finger mass, 15 mm) moves the skin 0.30 um, over the
    # 0.1 um threshold; a grasp (0.554 kg at 20 mm) only 0.017 um
    p = edits.new_project("time")
    p, drive = edits.add_track(p, "drive", "drive")
    p = edits.set_track(p, drive, full_scale=5e-4)
    p, buzz = edits.add_tile(p, generator("sine", 0.2, "buzz", frequency=250.0))
    p, _ = edits.add_clip(p, drive, buzz, 0.0)
    path = tmp_path / "buzz.htl"
    save(p, path)
    kinds = {}
    for hand in ("pinch", "grasp", "grasp-turn:45"):
        assert cli.main(["check", str(path), "--hand", hand, "--json"]) in (0, 3)
        report = json.loads(capsys.readouterr().out)
        assert report["hand"] == hand
        kinds[hand] = {f["kind"] for f in report["findings"]}
    assert "below-detection" not in kinds["pinch"]
    assert "below-detection" in kinds["grasp"]
    assert "below-detection" in kinds["grasp-turn:45"]
    assert cli.main(["check", str(path), "--hand", "free"]) == 0
    assert "detection not checked" in capsys.readouterr().err
    assert cli.main(["check", str(path), "--hand", "claw"]) == 1
    err = capsys.readouterr().err
    assert "cannot read hand 'claw'" in err and err.count("\n") == 1


def test_check_on_the_usb_knob_reports_the_sims_limits_for_its_declared_estimator(capsys) -> None:
    """The emulated firmware runs the Kalman observer with a one-period delay and declares
    both: `check --device usb` reports the delayed sim's limits (float32 on the wire apart)."""
    project = str(EXAMPLES / "fan_knob.htl")
    usb = ["--device", "usb", "--device-option", "emulate=true"]
    assert cli.main(["check", project, "--json", *usb]) == 0
    on_usb = json.loads(capsys.readouterr().out)
    assert cli.main(["check", project, "--json", "--device-option", "delay=1"]) == 0
    on_sim = json.loads(capsys.readouterr().out)
    assert on_usb["device"]["dynamics"]["estimator"] == "kalman"
    assert len(on_usb["device"]["dynamics"]["observer_gains"]) == 3
    for name in ("damping", "mass_low", "mass_high"):
        assert on_usb["limits"][name] == pytest.approx(on_sim["limits"][name], rel=1e-6)
    assert on_usb["limits"]["mass_high"] == pytest.approx(1.8044e-5, rel=1e-4)
    assert on_usb["limits"]["damping"] == pytest.approx(0.07811, rel=1e-4)
