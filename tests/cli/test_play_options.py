"""Device options from the command line, and the summary of a vibrotactile device."""

from pathlib import Path

import numpy as np
import pytest

from timeline.cli.device_options import parse_option
from timeline.cli.main import main
from timeline.errors import HapticTimelineError
from timeline.plugins.device_protocol import Telemetry

PROJECTS = Path(__file__).resolve().parents[2] / "projects"


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("emulate=true", ("emulate", True)),
        ("vid=0x1209", ("vid", 0x1209)),
        ("max-torque=0.05", ("max_torque", 0.05)),
        ("serial=ABC", ("serial", "ABC")),
        ("lead=off", ("lead", False)),
    ],
)
def test_parse_option(text, expected):
    assert parse_option(text) == expected


def test_parse_option_needs_an_equals_sign():
    with pytest.raises(HapticTimelineError, match="KEY=VALUE"):
        parse_option("emulate")


def test_usb_emulated_through_a_device_option(capsys):
    project = str(PROJECTS / "rising_resistance.htl")
    args = ["play", project, "--device", "usb", "--device-option", "emulate=true"]
    assert main([*args, "--duration", "0.2"]) == 0
    assert "on usb 1209:0001" in capsys.readouterr().out


def test_an_unknown_device_option_is_one_sentence(capsys):
    project = str(PROJECTS / "rising_resistance.htl")
    assert main(["play", project, "--device-option", "colour=red"]) == 1
    err = capsys.readouterr().err
    assert "the sim device does not take those options" in err and err.count("\n") == 1


def test_vibrotactile_summary_speaks_in_fractions_of_full_scale():
    n = 100
    z = np.zeros(n)
    torque = np.full(n, 0.25)
    tel = Telemetry(1000.0, np.arange(n) / 1000, z, z, torque, z, np.zeros(n, bool), {}, (), ())
    lines = tel.summary("vibrotactile")
    assert "peak output 25.0% of full scale" in lines
    assert not any("mNm" in line or "energy" in line for line in lines)
    assert "peak torque 250.00 mNm" in tel.summary()
