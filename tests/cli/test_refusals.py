"""Mistakes once accepted in silence, and messages that leaked internals: one sentence each,
naming the user's own choices, and a non-zero exit (issue 22 item 6, issue 25 items 2, 5, 8)."""

import shutil
import sys
from pathlib import Path

import numpy as np
import pytest

from device.usb import UsbKnob
from device.usb import driver as usb_driver
from device.usb.emulated import EmulatedBackend, EmulatedDevice
from device.usb.firmware import EmulatedKnob
from timeline.cli.devices_cmd import describe_devices
from timeline.cli.main import main
from timeline.plugins.device_protocol import CoefficientBlock, Hand

PROJECTS = Path(__file__).resolve().parents[2] / "projects"
FAN, BUZZ = str(PROJECTS / "fan_knob.htl"), str(PROJECTS / "notification_buzz.htl")


def refused(argv: list[str], capsys) -> str:
    """Run a verb that must be refused: exit 1 and one line on stderr, returned."""
    assert main(argv) == 1
    captured = capsys.readouterr()
    assert captured.err.count("\n") == 1 and "Traceback" not in captured.err, captured.err
    assert "playing" not in captured.err  # refused before any work
    return captured.err


def test_play_origin_outside_the_table(capsys):
    err = refused(["play", FAN, "--origin", "400", "--duration", "0.01"], capsys)
    assert "--origin 400 deg is outside fan_knob.htl's table (0 deg to 280 deg)" in err


def test_play_origin_on_a_time_project(capsys):
    err = refused(["play", BUZZ, "--origin", "10", "--duration", "0.01"], capsys)
    assert "--origin is where the knob starts on a position project's table" in err
    assert "notification_buzz.htl is on the time axis" in err


def test_render_start_before_zero_seconds(tmp_path, capsys):
    out = tmp_path / "o.csv"
    err = refused(["render", BUZZ, "-o", str(out), "--start", "-1"], capsys)
    assert "--start -1 s is before the timeline starts (0 s)" in err and not out.exists()


def test_play_telemetry_into_json(tmp_path, capsys):
    out = tmp_path / "tele.json"
    err = refused(["play", BUZZ, "-o", str(out), "--duration", "0.01"], capsys)
    assert "give a file ending in .csv, not .json" in err and not out.exists()


def test_import_into_a_project_not_named_htl(tmp_path, capsys):
    source = tmp_path / "x.csv"
    source.write_text("time,value\n0,0\n0.001,0.5\n0.002,1\n")
    into = tmp_path / "p.txt"
    err = refused(["import", str(source), "--into", str(into)], capsys)
    assert "--into names the project file, which ends in .htl: p.txt does not" in err
    assert not into.exists()


def test_import_into_a_missing_folder_names_the_users_path(tmp_path, capsys):
    source = tmp_path / "x.csv"
    source.write_text("time,value\n0,0\n0.001,0.5\n0.002,1\n")
    into = tmp_path / "missing" / "dir" / "p.htl"
    err = refused(["import", str(source), "--into", str(into)], capsys)
    assert f"cannot write {into}: the folder {into.parent} does not exist" in err
    assert ".partial" not in err


def test_export_fixed_point_outside_firmware_tables(tmp_path, capsys):
    out = tmp_path / "x.csv"
    err = refused(["export", BUZZ, "-o", str(out), "--fixed-point"], capsys)
    assert "--fixed-point applies to firmware tables (.h, .json), not to a .csv" in err
    assert not out.exists()


@pytest.mark.parametrize("suffix", [".ahap", ".haptic"])
def test_a_position_project_to_a_vibration_design_says_why(tmp_path, capsys, suffix):
    err = refused(["export", FAN, "-o", str(tmp_path / f"fan{suffix}")], capsys)
    assert "is vibration over time, and fan_knob.htl is a position project with no time axis" in err


def test_a_duration_beyond_one_play_is_said_in_seconds_and_hours(capsys):
    err = refused(["play", BUZZ, "--duration", "1e9"], capsys)
    assert "--duration 1e+09 s is longer than sim can play in one go" in err
    assert "(214748 s, 59.7 hours, at 10000 Hz)" in err and "render_chunks" not in err


def test_an_unknown_device_option_lists_the_valid_ones(capsys):
    err = refused(["play", BUZZ, "--device-option", "bogus=1"], capsys)
    assert "the sim device does not take those options (bogus); it takes integrator" in err
    assert "max_torque" in err and "KnobParams" not in err and "__init__" not in err
    err = refused(["play", BUZZ, "--device", "usb", "--device-option", "colour=red"], capsys)
    assert "usb device does not take those options (colour); it takes vid, pid, serial" in err
    assert "backend" not in err


@pytest.mark.parametrize(
    ("option", "sentence"),
    [
        ("max_torque=abc", "the USB max_torque is a torque cap in N*m, 0 (no torque) or more, "
         "not 'abc'"),
        ("max_torque=-1", "the USB max_torque is a torque cap in N*m, 0 (no torque) or more, "
         "not -1"),
        ("vid=0x10000", "the USB vid is a whole number from 0 to 0xffff (16 bits), not 0x10000"),
        ("watchdog_ms=0.5", "the USB watchdog_ms is a whole number from 5 to 1000, not 0.5"),
    ],
)  # fmt: skip
def test_usb_option_values_it_cannot_use(option, sentence, capsys):
    argv = ["play", BUZZ, "--device", "usb", "--device-option", "emulate=true"]
    assert sentence in refused([*argv, "--device-option", option], capsys)


def test_sim_option_values_it_cannot_use(capsys):
    err = refused(["play", BUZZ, "--device-option", "max_torque=abc"], capsys)
    assert "the knob's max torque (max_torque) is a number, not 'abc'" in err
    err = refused(["play", BUZZ, "--device-option", "max_torque=0"], capsys)
    assert "the simulated knob's max torque is its motor's own limit and must be above 0" in err


def test_a_usb_torque_cap_of_zero_plays_no_torque(tmp_path, capsys):
    out = tmp_path / "t.csv"
    argv = ["play", BUZZ, "--device", "usb", "--device-option", "emulate=true", "-o", str(out)]
    assert main([*argv, "--device-option", "max_torque=0", "--duration", "0.05"]) == 0
    assert "peak torque 0.00 mNm" in capsys.readouterr().out
    torque = np.loadtxt(out, delimiter=",", skiprows=1)[:, 3]
    assert len(torque) == 500 and not torque.any()


def test_a_vibrotactile_device_states_its_limit_as_a_share_of_full_scale():
    knob = UsbKnob(backend=EmulatedBackend(EmulatedDevice(EmulatedKnob(vibrotactile=True))))
    d, zero = np.full(200, 1.5), np.zeros(200)
    telemetry = knob.play([CoefficientBlock(d, zero, zero)], Hand("hold"))
    clamped = [w for w in telemetry.warnings if "clamped" in w]
    assert clamped == [
        "200 values were clamped to the device's limits (max output 100% of full scale)"
    ]


def test_devices_says_which_library_is_missing(monkeypatch):
    monkeypatch.setitem(sys.modules, "sounddevice", None)  # not installed
    monkeypatch.setattr(usb_driver, "default_backend", lambda: None)  # no libusb
    monkeypatch.delenv(usb_driver.EMULATE_ENV, raising=False)
    lines = describe_devices()
    audio = next(line for line in lines if line.startswith("audio: "))
    usb = next(line for line in lines if line.startswith("usb: "))
    assert audio == (
        "audio: nothing found (the audio device needs the sounddevice package: "
        "pip install 'haptic-timeline[audio]')"
    )
    assert usb.startswith("usb: nothing found (no USB library was found: install libusb")
    assert main(["devices"]) == 0  # a listing: each plugin's line says what it found


def test_refusals_leave_the_project_untouched(tmp_path, capsys):
    project = tmp_path / "fan.htl"
    shutil.copy(FAN, project)
    before = project.read_bytes()
    source = tmp_path / "x.csv"
    source.write_text("time,value\n0,0\n0.001,0.5\n0.002,1\n")
    refused(["import", str(source), "--into", str(project), "--at", "2s"], capsys)
    refused(["import", str(source), "--into", str(project), "--length", "1s"], capsys)
    assert project.read_bytes() == before


def test_running_out_of_memory_on_import_names_the_file_not_a_range(tmp_path, monkeypatch, capsys):
    from timeline.files import importing

    def too_big(*args, **kwargs):
        raise MemoryError

    monkeypatch.setattr(importing, "read_file", too_big)
    source = tmp_path / "big.csv"
    source.write_text("time,value\n0,0\n0.001,0.5\n")
    err = refused(["import", str(source), "--into", str(tmp_path / "p.htl")], capsys)
    assert f"ran out of memory reading {source}: it needs more memory than is free" in err
    assert "range" not in err and not (tmp_path / "p.htl").exists()
