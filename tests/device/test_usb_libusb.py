"""With the real libusb and no device attached: finding returns nothing, `play` says so."""

from __future__ import annotations

from pathlib import Path

import pytest
import usb.core

from device.usb import UsbKnob
from device.usb.driver import EMULATE_ENV
from device.usb.link import default_backend, find_devices
from timeline.cli.devices_cmd import describe_devices
from timeline.cli.main import main

PROJECT = Path(__file__).resolve().parents[2] / "projects" / "notification_buzz.htl"


@pytest.fixture
def libusb(monkeypatch: pytest.MonkeyPatch):
    monkeypatch.delenv(EMULATE_ENV, raising=False)
    backend = default_backend()
    if backend is None:
        pytest.skip("no libusb-1.0 could be loaded here (apt-get install libusb-1.0-0)")
    if find_devices(0x1209, 0x0001, backend):
        pytest.skip("a real haptic-timeline device (1209:0001) is attached")
    return backend


def test_the_real_libusb_enumerates_without_failing(libusb) -> None:
    assert isinstance(list(usb.core.find(find_all=True, backend=libusb)), list)
    assert find_devices(0x1209, 0x0001, libusb) == []
    assert UsbKnob.discover() == []


def test_the_devices_verb_lists_nothing_found_for_usb(libusb) -> None:
    assert "usb: nothing found" in describe_devices()


def test_play_on_usb_without_a_device_exits_non_zero_with_one_sentence(libusb, capsys) -> None:
    code = main(["play", str(PROJECT), "--device", "usb"])
    err = capsys.readouterr().err.strip().splitlines()
    assert code != 0
    assert err[-1] == (
        "haptic-timeline: no USB haptic device 1209:0001 found (check the cable and "
        "permissions, or use the sim device)"
    )
    assert not any("Traceback" in line for line in err)


def test_play_on_the_emulated_usb_device_works_from_the_cli(monkeypatch, capsys) -> None:
    monkeypatch.setenv(EMULATE_ENV, "1")
    assert main(["play", str(PROJECT), "--device", "usb"]) == 0
    out = capsys.readouterr().out
    assert "notification_buzz.htl on usb 1209:0001" in out
    assert "played 0.500 s (5000 samples at 10000 Hz)" in out
