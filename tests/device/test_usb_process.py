"""The USB stream in its own process: what goes wrong there comes back as the same one sentence."""

from __future__ import annotations

import time

import numpy as np
import pytest

from device.usb import UsbKnob
from device.usb.errors import DeviceUnderrun, UsbDeviceError
from timeline.errors import HapticTimelineError
from timeline.plugins.device_protocol import CoefficientBlock, Hand


def blocks(count: int, n: int = 100):
    """10 ms blocks of a 50 mNm drive."""
    return [CoefficientBlock(np.full(n, 0.05), np.zeros(n), np.zeros(n)) for _ in range(count)]


@pytest.fixture
def knob():
    knob = UsbKnob(emulate=True, realtime=True)
    knob.open()
    yield knob
    knob.close()


def test_a_real_time_knob_streams_from_its_own_process_with_a_longer_lead(knob):
    assert knob.remote is not None and knob.remote.process.is_alive()
    assert (knob.lead, knob.watchdog_ms) == (0.1, 120)
    assert knob.info.lead == pytest.approx(0.12)  # the lead and two blocks, handed over ahead
    tel = knob.play(blocks(30), Hand("hold"))
    assert len(tel) == 3000 and knob.underruns == 0 and tel.lateness.late == 0


def test_a_host_late_past_the_lead_underruns_the_knob_and_hears_the_sentence(knob):
    def late():
        for i, block in enumerate(blocks(40)):
            if i == 20:  # the host held up 300 ms: past the 100 ms lead and 120 ms watchdog
                time.sleep(0.3)
            yield block

    with pytest.raises(DeviceUnderrun, match=r"ran out of samples at .* because the host fell"):
        knob.play(late(), Hand("hold"))
    tel = knob.play(blocks(20), Hand("hold"))  # the process plays on after an error
    assert len(tel) == 2000 and knob.underruns == 0


def test_a_stream_process_that_died_is_one_sentence(knob):
    knob.remote.process.kill()
    knob.remote.process.join()
    with pytest.raises(UsbDeviceError, match=r"^the USB stream process ended unexpectedly \(exit"):
        knob.play(blocks(5), Hand("hold"))


def test_an_error_of_the_blocks_source_comes_back_from_play(knob):
    def failing():
        yield from blocks(15)
        raise HapticTimelineError("the clip could not be rendered")

    with pytest.raises(HapticTimelineError, match="^the clip could not be rendered$"):
        knob.play(failing(), Hand("hold"))
