"""The host stops when the USB device says a NaN or infinity reached its coefficients."""

from __future__ import annotations

import struct
import zlib

import numpy as np
import pytest

from device.usb import UsbKnob
from device.usb import protocol as p
from device.usb.emulated import EmulatedBackend, EmulatedDevice
from device.usb.errors import DeviceFault
from device.usb.firmware import EmulatedKnob
from timeline.plugins.device_protocol import CoefficientBlock, Hand


def test_a_non_finite_flag_from_the_device_stops_playback(monkeypatch) -> None:
    emulated = EmulatedDevice(EmulatedKnob(), record=True)
    knob = UsbKnob(backend=EmulatedBackend(emulated))
    device = emulated.knob
    real = device.receive
    blocks: list[bytes] = []

    def receive(data: bytes) -> None:  # the third block holds a NaN (its CRC intact): zeroed
        blocks.append(data)
        if len(blocks) == 3:
            body = bytearray(data[:-4])
            struct.pack_into("<f", body, p.BLOCK_HEADER_SIZE, float("nan"))
            data = bytes(body) + struct.pack("<I", zlib.crc32(body))
        real(data)

    monkeypatch.setattr(device, "receive", receive)
    steady = [CoefficientBlock(np.full(1000, 0.05), np.full(1000, 0.5), np.zeros(1000))] * 5
    with pytest.raises(DeviceFault, match=r"reported non-finite at .*; playback stopped"):
        knob.play(steady, Hand("hold"))
    assert device.state == p.STATE_RAMPING  # STOP arrived: the device ramps to zero
