"""A real-time emulated USB knob played the way `haptic-timeline play` plays it, while another
thread holds the interpreter in pure-Python loops: the host's pacing must absorb the wait for
the interpreter lock (docs/usb-protocol.md, section 4), so the knob never runs dry."""

from __future__ import annotations

from contextlib import AbstractContextManager, nullcontext
from pathlib import Path

import numpy as np

from timeline.files.projectfile import load
from timeline.plugins.device_protocol import Hand, open_device
from timeline.rendering.playback import prepare

PROJECT = Path(__file__).parents[2] / "projects" / "rising_resistance.htl"


def played(realtime: bool, busy: AbstractContextManager[None] | None) -> tuple[np.ndarray, int]:
    """The CLI's steps (open, prepare, warm up, play): torque reported, and samples the knob
    played from an empty queue."""
    project = load(PROJECT)
    hand = Hand("hold")
    with open_device("usb", emulate=True, realtime=realtime) as device:
        playback = prepare(project, device.info, None, hand)
        device.warm_up()
        with busy or nullcontext():
            telemetry = device.play(playback.program, hand)
    return telemetry.torque, device.underruns


def test_a_real_time_knob_starved_of_the_interpreter_lock_does_not_underrun(busy_interpreter):
    torque, underruns = played(realtime=True, busy=busy_interpreter())
    assert underruns == 0
    expected, _ = played(realtime=False, busy=None)  # the same firmware, paced by the host's reads
    assert len(torque) == 20_000
    np.testing.assert_array_equal(torque, expected)
