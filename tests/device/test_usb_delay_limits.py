"""A USB knob declares its one-period computation delay, and the host checks against the
delayed limits: each flagged just above its bound, not at it nor just below."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from device.usb import UsbKnob
from device.usb.emulated import EmulatedBackend, EmulatedDevice
from tests.limits.designs import layered
from timeline.files.projectfile import load
from timeline.limits import servo
from timeline.limits.check import check
from timeline.plugins.device_protocol import CoefficientBlock, Hand

PROJECTS = Path(__file__).resolve().parents[2] / "projects"
JUST = 1e-6  # relative step either side of a limit


@pytest.fixture(scope="module")
def knob() -> UsbKnob:
    return UsbKnob(backend=EmulatedBackend(EmulatedDevice()))


def test_the_emulated_knob_declares_a_one_period_delay(knob: UsbKnob) -> None:
    dyn = knob.info.dynamics
    assert dyn.delay == 1
    # (b_dev - |B|) / (T (1/2 + 1)) with b_dev = 1e-4 (float32 on the wire) and T = 0.1 ms
    assert servo.passive_stiffness(dyn.damping, 0.0, knob.info.period, 1) == pytest.approx(
        2 / 3, rel=1e-6
    )


def _limit(knob: UsbKnob, layer: str, delay: int = 1) -> float:
    dyn, period = replace(knob.info.dynamics, delay=delay), knob.info.period
    if layer == "stiffness":
        return servo.passive_stiffness(dyn.damping, 0.0, period, dyn.delay)
    if layer == "damping":
        return servo.damping_limit(dyn, period)
    return servo.mass_limits(dyn, period)[1]


@pytest.mark.parametrize("layer", ["stiffness", "damping", "mass"])
@pytest.mark.parametrize(("scale", "found"), [(1 - JUST, False), (1.0, False), (1 + JUST, True)])
def test_the_delayed_limits_are_flagged_on_the_usb_knob(
    knob: UsbKnob, layer: str, scale: float, found: bool
) -> None:
    limit = _limit(knob, layer)
    assert limit < 0.9 * _limit(knob, layer, delay=0)  # the delay lowers every limit
    kinds = [f.kind for f in check(layered(layer, limit * scale), knob.info).findings]
    assert (f"{layer}-limit" in kinds) == found


@pytest.mark.parametrize("name", ["fan_knob.htl", "notification_buzz.htl", "rising_resistance.htl"])
def test_the_examples_are_quiet_on_the_usb_knob(knob: UsbKnob, name: str) -> None:
    assert check(load(PROJECTS / name), knob.info).findings == ()


@pytest.mark.parametrize(("k", "flagged"), [(0.6, 0), (0.7, 500)])
def test_streaming_flags_a_spring_above_the_delayed_bound(k: float, flagged: int) -> None:
    """0.7 N*m/rad is below the undelayed 2.0 but above the delayed 0.667: every sample flagged."""
    usb = UsbKnob(backend=EmulatedBackend(EmulatedDevice()))
    n = 500
    block = CoefficientBlock(np.full(n, 0.01), np.full(n, k), np.zeros(n))
    tel = usb.play([block], Hand("hold"))
    assert sum(f.count for f in tel.flags if f.kind == "passivity") == flagged
