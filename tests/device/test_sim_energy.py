"""The energy telemetry against the closed form of a damped oscillator (issue 20).

A hand holds the knob through a spring-damper (grip K, B); the motor kicks it and lets go. From
then on the knob is a damped oscillator (J + J_h) theta'' + (b_dev + B) theta' + K theta = 0, both
dampers dissipate in proportion to omega^2, so of the motor's work W (exact: the torque is held
over each period, W = sum tau_i (theta_i+1 - theta_i)) the device's own damping b_dev takes
b_dev/(b_dev + B) of what is no longer stored: the energy the device put in is
E = W - b_dev/(b_dev + B) * (W - E_mech), E_mech = (J + J_h) omega^2/2 + K theta^2/2 now.
"""

from __future__ import annotations

import numpy as np
import pytest

from device.sim import KnobParams, KnobPhysics
from timeline.plugins.device_protocol import CoefficientBlock, Hand


@pytest.mark.parametrize("grip_damping", [1e-4, 5e-3])
@pytest.mark.parametrize("integrator", ["zoh", "rk4"])
def test_energy_after_a_decayed_ring_is_the_exact_integral(
    grip_damping: float, integrator: str
) -> None:
    p = KnobParams(quantum=0.0, coulomb=0.0)
    hand = Hand("hold", grip_stiffness=1.0, grip_damping=grip_damping, inertia=2e-5)
    knob = KnobPhysics(p, integrator=integrator)
    knob.start(hand)
    n = 20_000  # 2 s: the 29 Hz ring decays by 1e-4 or more
    d, zero = np.zeros(n), np.zeros(n)
    d[:20] = 0.02
    tel = knob.run_block(CoefficientBlock(d, zero, zero))
    path = np.append(tel.angle, knob.theta)  # ideal sensor: the reading is the true angle
    work = float(np.sum(tel.torque * np.diff(path)))
    stored = 0.5 * (p.inertia + hand.inertia) * knob.omega**2 + 0.5 * knob.theta**2
    share = p.viscous / (p.viscous + grip_damping)
    exact = work - share * (work - stored)
    assert stored < 1e-3 * work  # the ring has decayed
    assert tel.energy[-1] == pytest.approx(exact, rel=1e-6)


def test_a_fast_free_ring_loses_what_the_closed_form_says() -> None:
    """Free knob spinning down from a kick: all the motor's work goes into b_dev, E -> 0 + E_kin
    (the rectangle rule undercounted the loss and left most of the kick's work reported)."""
    p = KnobParams(quantum=0.0, coulomb=0.0, inertia=1e-6)
    knob = KnobPhysics(p)
    knob.start(Hand("free"))
    n = 5000
    d, zero = np.zeros(n), np.zeros(n)
    d[:10] = 0.01
    tel = knob.run_block(CoefficientBlock(d, zero, zero))
    path = np.append(tel.angle, knob.theta)
    work = float(np.sum(tel.torque * np.diff(path)))
    kinetic = 0.5 * p.inertia * knob.omega**2
    assert tel.energy[-1] == pytest.approx(kinetic, abs=1e-6 * work)
