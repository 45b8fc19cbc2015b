"""USB fault campaigns and device safety invariants, under hypothesis.

Faults: a transfer that times out, stalls, arrives late (underrun), never comes back (unplug),
has one bit flipped, or carries a report whose torque is NaN, 1e30 or beyond the limit. Each
play either completes with telemetry equal in length to what was sent, or stops with one
sentence; either way the device ends at exactly zero torque within watchdog + ramp (60 ms).
Invariants: whatever coefficients are played (NaN, inf, 1e308 included), the torque reaching
the motor is finite and never above the declared maximum, NaN/inf is flagged, and once blocks
stop arriving the torque is exactly zero after watchdog + ramp.
"""

from __future__ import annotations

import math

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from device.sim import KnobParams, KnobPhysics, SimKnob
from device.usb import UsbKnob
from device.usb import protocol as p
from device.usb.emulated import EmulatedBackend, EmulatedDevice, FaultPlan
from timeline.plugins.device_protocol import CoefficientBlock, DeviceError, Hand

from .conftest import count

FAULT_CAMPAIGN = 40
INVARIANT_EXAMPLES = 40
SETTINGS = {"deadline": None, "database": None, "suppress_health_check": [HealthCheck.too_slow]}

transfer = st.integers(0, 14)
faults = st.one_of(
    st.builds(FaultPlan, timeout_at=transfer),
    st.builds(FaultPlan, stall_at=transfer),
    st.builds(FaultPlan, late_at=transfer),
    st.builds(FaultPlan, unplug_after=transfer),
    st.builds(FaultPlan, flip_bit_at=st.tuples(transfer, st.integers(0, 8 * 1236 - 1))),
    st.builds(
        FaultPlan,
        lie_at=st.tuples(transfer, st.sampled_from([math.nan, math.inf, -1e30, 1e30, 0.2, -0.19])),
    ),
)


@settings(max_examples=count(FAULT_CAMPAIGN), **SETTINGS)
@given(faults, st.floats(0.0, 0.1), st.floats(0.0, 2.0))
def test_every_injected_usb_fault_ends_safe_with_one_sentence(plan, d, k) -> None:
    emulated = EmulatedDevice(faults=plan)
    knob = UsbKnob(backend=EmulatedBackend(emulated))
    n = 4000
    blocks = [CoefficientBlock(np.full(500, d), np.full(500, k), np.zeros(500)) for _ in range(8)]
    try:
        tel = knob.play(blocks, Hand("hold"))
    except DeviceError as exc:
        assert str(exc) and "\n" not in str(exc)
    else:
        assert len(tel) == n and np.isfinite(tel.torque).all()
    device = emulated.knob
    device.advance(0.050 + 0.0102)  # watchdog + ramp + the one-period delay: the motor is off
    assert (device.state, device.torque) == (p.STATE_IDLE, 0.0)


coefficient = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.floats(-1e3, 1e3),
    st.sampled_from([0.0, 1e308, -1e308, math.nan, math.inf, -math.inf]),
)


@settings(max_examples=count(INVARIANT_EXAMPLES), **SETTINGS)
@given(
    st.lists(st.tuples(coefficient, coefficient, coefficient), min_size=1, max_size=300),
    st.sampled_from(["hold", "free", "turn:200", "push:20"]),
)
def test_the_motor_never_sees_nan_or_more_than_its_maximum(rows, hand) -> None:
    d, k, b = (np.array(c, dtype=np.float64) for c in zip(*rows, strict=True))
    sim = SimKnob()
    tel = sim.play([CoefficientBlock(d, k, b)], Hand.parse(hand))
    limit = sim.info.max_output
    assert np.isfinite(tel.torque).all()
    assert np.abs(tel.torque).max(initial=0.0) <= limit
    if not (np.isfinite(d) & np.isfinite(k) & np.isfinite(b)).all():
        assert tel.flag("non-finite") is not None  # played as zero, never silently
    physics = KnobPhysics()
    physics.start(Hand.parse(hand))
    physics.run_block(CoefficientBlock(d, k, b))
    idle = physics.run_idle(int(0.1 * physics.params.rate))  # no more blocks: watchdog
    assert np.isfinite(idle.torque).all() and np.abs(idle.torque).max(initial=0) <= limit
    params = physics.params
    off = idle.time - idle.time[0] >= params.watchdog_timeout + params.watchdog_ramp - 1e-9
    assert off.any() and (idle.torque[off] == 0.0).all()  # off within watchdog + ramp


@settings(max_examples=count(INVARIANT_EXAMPLES), **SETTINGS)
@given(
    st.lists(st.tuples(coefficient, coefficient, coefficient), min_size=1, max_size=300),
    st.sampled_from(["hold", "free", "turn:200", "push:20"]),
    st.one_of(st.floats(1.0, 1e4), st.sampled_from([0.5, 18.0, 1800.0, 1e6])),
    st.sampled_from([0, 1]),
)
def test_a_declared_slew_limit_is_never_exceeded(rows, hand, slew, delay) -> None:
    d, k, b = (np.array(c, dtype=np.float64) for c in zip(*rows, strict=True))
    physics = KnobPhysics(KnobParams(slew=slew, delay=delay))
    physics.start(Hand.parse(hand))
    played = physics.run_block(CoefficientBlock(d, k, b))
    idle = physics.run_idle(int(0.02 * physics.params.rate))  # the watchdog's ramp as well
    torque = np.concatenate([[0.0], played.torque, idle.torque])  # the motor starts at rest
    step = slew * physics.params.period
    assert np.isfinite(torque).all()
    assert np.abs(torque).max() <= physics.params.max_torque
    assert np.abs(np.diff(torque)).max() <= step * (1 + 1e-12) + 1e-15  # rounding only
    assert SimKnob(slew=slew).info.slew == slew  # what `check` and the host are told
