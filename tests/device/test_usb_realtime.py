"""The emulated USB knob on the wall clock: a host that falls behind underruns it, and its
watchdog ramps the torque to zero, as on hardware (docs/usb-protocol.md, sections 4 and 6)."""

from __future__ import annotations

import time as wall

import numpy as np
import pytest

from device.usb import UsbKnob
from device.usb import protocol as p
from device.usb.emulated import EmulatedBackend, EmulatedDevice
from device.usb.errors import DeviceUnderrun
from timeline.plugins.device_protocol import CoefficientBlock, Hand


def blocks(count: int = 30, n: int = 100):
    """10 ms blocks of a 50 mNm drive."""
    return [CoefficientBlock(np.full(n, 0.05), np.zeros(n), np.zeros(n)) for _ in range(count)]


class VirtualTime:
    """A wall clock that moves only when someone waits on it: the device's real-time logic,
    deterministic whatever the machine's load."""

    def __init__(self) -> None:
        self.now = 0.0

    def clock(self) -> float:
        return self.now

    def sleep(self, seconds: float) -> None:
        self.now += seconds


def test_a_starved_real_time_knob_underruns_and_ramps_to_zero():
    time = VirtualTime()
    emulated = EmulatedDevice(realtime=True, clock=time.clock, sleep=time.sleep)
    knob = UsbKnob(backend=EmulatedBackend(emulated))

    def starved():
        for i, block in enumerate(blocks()):
            if i == 4:  # the host held up 150 ms: past the 30 ms lead and the 50 ms watchdog
                time.sleep(0.15)
            yield block

    with pytest.raises(DeviceUnderrun, match=r"ran out of samples at 0\.030 s \(204 samples"):
        knob.play(starved(), Hand("hold"))
    device = emulated.knob
    assert device.last_block_seq == 3  # the lead, one block after the first report, then none
    assert device.flags & p.FLAG_UNDERRUN and device.flags & p.FLAG_WATCHDOG
    assert device.underruns > 0
    device.advance(0.02)
    assert (device.state, device.torque) == (p.STATE_IDLE, 0.0)


def test_a_host_read_driven_knob_is_never_late():
    """Without the wall clock the device waits for the host however slow it is."""
    emulated = EmulatedDevice()
    knob = UsbKnob(backend=EmulatedBackend(emulated))

    def slow():
        for i, block in enumerate(blocks(8)):
            if i == 4:
                wall.sleep(0.15)
            yield block

    tel = knob.play(slow(), Hand("hold"))
    assert len(tel) == 800 and emulated.knob.underruns == 0 and tel.lateness is None
