"""Every device reports telemetry live through the monitor, matching what it returns at the end."""

import numpy as np
import pytest

from device.sim import KnobParams, SimKnob, passive_stiffness
from device.usb import UsbKnob
from timeline.plugins.device_protocol import CoefficientBlock, Hand


def blocks(n_blocks=5, n=200):
    t = np.arange(n_blocks * n) / 10_000
    d = 0.05 * np.sin(2 * np.pi * 20 * t)
    k = np.full_like(t, 0.5)
    return [CoefficientBlock(d[i : i + n], k[i : i + n], np.zeros(n)) for i in range(0, len(t), n)]


@pytest.mark.parametrize("make", [SimKnob, lambda: UsbKnob(emulate=True)])
def test_monitor_pieces_add_up_to_the_telemetry(make):
    pieces = []
    with make() as device:
        tel = device.play(blocks(), Hand("hold"), monitor=pieces.append)
    assert len(pieces) >= 2
    time = np.concatenate([p.time for p in pieces])
    np.testing.assert_allclose(time, tel.time)
    np.testing.assert_array_equal(np.concatenate([p.angle for p in pieces]), tel.angle)
    np.testing.assert_array_equal(np.concatenate([p.torque for p in pieces]), tel.torque)
    assert np.abs(tel.torque).max() > 0.01


def test_a_monitored_sim_play_plays_the_same_torque_without_judging_it():
    p = KnobParams()
    limit = passive_stiffness(p.viscous, 0.0, p.period, p.delay)
    n = 100
    d = np.zeros(n)
    d[:5] = 0.01
    spring = [CoefficientBlock(d, np.full(n, 1.5 * limit), np.zeros(n))]  # past passivity
    judged = SimKnob().play(spring, Hand("hold"))
    watched = SimKnob().play(spring, Hand("hold"), monitor=lambda part: None)
    assert "passivity" in {f.kind for f in judged.flags}
    assert watched.flags == ()  # the editor, which monitors, judges the design itself
    np.testing.assert_array_equal(watched.torque, judged.torque)
