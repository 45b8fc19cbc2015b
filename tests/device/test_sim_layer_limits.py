"""Damping and virtual-mass limits: computed from the servo loop, flagged at the boundary, felt.

The sim's estimators stay on (its defaults: the velocity filter, the Kalman observer of the
acceleration); quantisation and Coulomb friction are off, so the knob is the linear loop the
limits are computed on.
"""

from __future__ import annotations

import numpy as np
import pytest

from device.sim import KnobParams, KnobPhysics, stability_flags
from timeline.limits import servo
from timeline.plugins.device_protocol import CoefficientBlock, Dynamics, Hand

LINEAR = dict(quantum=0.0, coulomb=0.0)


def test_damping_limit_is_two_inertias_per_period_with_a_raw_estimate() -> None:
    dyn = Dynamics(inertia=1e-5, damping=0.0)
    assert servo.damping_limit(dyn, 1e-4) == pytest.approx(2 * 1e-5 / 1e-4, rel=1e-6)


def test_stable_stiffness_matches_the_reference_and_the_delayed_passivity_bound() -> None:
    assert servo.stable_stiffness(Dynamics(1e-5, 1e-4), 1e-4) == pytest.approx(2.0, rel=1e-3)
    delayed = Dynamics(1e-5, 1e-4, delay=1)
    assert servo.stable_stiffness(delayed, 1e-4) == pytest.approx(
        servo.passive_stiffness(1e-4, 0.0, 1e-4, 1), rel=1e-3
    )
    assert servo.passive_stiffness(1e-4, 0.0, 1e-4, 1) == pytest.approx(2.0 / 3.0)


def test_a_delay_lowers_every_limit() -> None:
    now, late = Dynamics(1e-5, 1e-4, 0, 2000, 200), Dynamics(1e-5, 1e-4, 1, 2000, 200)
    assert servo.damping_limit(late, 1e-4) < 0.5 * servo.damping_limit(now, 1e-4)
    assert servo.mass_limits(late, 1e-4)[1] < 0.5 * servo.mass_limits(now, 1e-4)[1]


@pytest.mark.parametrize(
    ("layer", "fraction", "flagged"),
    [("b", 0.999, False), ("b", 1.0, False), ("b", 1.001, True), ("m", 0.999, False),
     ("m", 1.0, False), ("m", 1.001, True), ("m-", 0.999, False), ("m-", 1.001, True)],
)  # fmt: skip
def test_flags_fire_just_above_the_limit(layer: str, fraction: float, flagged: bool) -> None:
    p = KnobParams()
    low, high = servo.mass_limits(p.dynamics, p.period)
    limit = {"b": servo.damping_limit(p.dynamics, p.period), "m": high, "m-": low}[layer]
    value = np.array([fraction * limit])
    zero = np.zeros(1)
    damping = value if layer == "b" else zero
    mass = zero if layer == "b" else value
    kinds = {
        f.kind for f in stability_flags(np.zeros(1), zero, damping, mass, p.dynamics, p.period)
    }
    # with the knob's own damping the lowest stable mass is -J: below it the inertia is cancelled
    name = {"b": "damping-limit", "m": "mass-limit", "m-": "mass-cancels-inertia"}[layer]
    assert (name in kinds) == flagged
    if flagged:
        flags = stability_flags(np.zeros(1), zero, damping, mass, p.dynamics, p.period)
        flag = next(f for f in flags if f.kind == name)
        assert flag.margins[0] == pytest.approx(abs(0.001 * limit), rel=1e-6)


def _kicked(layer: str, value: float, seconds: float = 0.4, delay: int = 0) -> np.ndarray:
    """A free linear knob rendering one layer at a constant value after a short kick: its torque."""
    p = KnobParams(**LINEAR, delay=delay)
    knob = KnobPhysics(p)
    knob.start(Hand("free"))
    n = int(seconds * p.rate)
    d = np.zeros(n)
    d[:5] = 1e-3
    zero = np.zeros(n)
    b = np.full(n, value) if layer == "b" else zero
    m = np.full(n, value) if layer == "m" else zero
    k = np.full(n, value) if layer == "k" else zero
    tel = knob.run_block(CoefficientBlock(d, k, b, m))
    return tel.torque


@pytest.mark.parametrize("layer", ["b", "m"])
@pytest.mark.parametrize("fraction", [0.95, 1.05])
def test_knob_rings_down_below_the_limit_and_chatters_above(layer: str, fraction: float) -> None:
    p = KnobParams(**LINEAR)
    limit = (
        servo.damping_limit(p.dynamics, p.period)
        if layer == "b"
        else servo.mass_limits(p.dynamics, p.period)[1]
    )
    torque = _kicked(layer, fraction * limit)
    early = np.abs(torque[10:1000]).max()
    late = np.abs(torque[-800:]).max()
    if fraction < 1:
        assert late < 0.5 * early
    else:  # the kick of 1 mNm grows into chatter at the amplifier's limit
        assert late > 0.9 * p.max_torque and late > 100 * np.abs(torque[10:20]).max()


@pytest.mark.parametrize("layer", ["k", "b", "m"])
@pytest.mark.parametrize("fraction", [0.95, 1.05])
def test_a_one_period_delay_lowers_the_limits_the_knob_obeys(layer: str, fraction: float) -> None:
    p = KnobParams(**LINEAR, delay=1)
    dyn, period = p.dynamics, p.period
    assert dyn.delay == 1
    limit = {
        "k": servo.passive_stiffness(dyn.damping, 0.0, period, 1),
        "b": servo.damping_limit(dyn, period),
        "m": servo.mass_limits(dyn, period)[1],
    }[layer]
    torque = _kicked(layer, fraction * limit, seconds=3.0 if layer == "k" else 0.4, delay=1)
    early = np.abs(torque[10:1000]).max()
    late = np.abs(torque[-800:]).max()
    if fraction < 1:  # the spring's 40 Hz ring decays slowly this close to the edge
        assert late < 0.8 * early
    else:
        assert late > 1.2 * early or late > 0.9 * p.max_torque  # grows, or chatters at the clamp


def test_the_delay_holds_the_torque_one_period() -> None:
    now, late = KnobPhysics(KnobParams(**LINEAR)), KnobPhysics(KnobParams(**LINEAR, delay=1))
    d = np.array([0.0, 0.01, 0.02, 0.0, 0.0])
    zero = np.zeros(5)
    a = now.run_block(CoefficientBlock(d, zero, zero)).torque
    b = late.run_block(CoefficientBlock(d, zero, zero)).torque
    np.testing.assert_array_equal(b, np.concatenate([[0.0], a[:-1]]))


@pytest.mark.parametrize("estimator", ["tracking", "kalman"])
@pytest.mark.parametrize("layer", ["b", "m"])
@pytest.mark.parametrize("fraction", [0.95, 1.05])
def test_with_an_observer_the_limits_follow_it(estimator: str, layer: str, fraction: float) -> None:
    p = KnobParams(**LINEAR, estimator=estimator)
    dyn, period = p.dynamics, p.period
    assert dyn.observer_gains == tuple(p.observer_gains)
    limit = servo.damping_limit(dyn, period) if layer == "b" else servo.mass_limits(dyn, period)[1]
    knob = KnobPhysics(p)
    knob.start(Hand("free"))
    n = 4000
    d = np.zeros(n)
    d[:5] = 1e-3
    zero = np.zeros(n)
    value = np.full(n, fraction * limit)
    tel = knob.run_block(
        CoefficientBlock(d, zero, value if layer == "b" else zero, value if layer == "m" else zero)
    )
    early, late = np.abs(tel.torque[10:1000]).max(), np.abs(tel.torque[-800:]).max()
    if fraction < 1:
        assert late < 0.5 * early
    else:
        assert late > 1.2 * early or late > 0.9 * p.max_torque


def test_a_declared_slew_limit_is_obeyed_and_checked() -> None:
    from timeline import edits, generator
    from timeline.limits.check import check
    from timeline.plugins.device_protocol import open_device

    p = KnobParams(**LINEAR, slew=100.0)  # N*m/s: 10 mNm per period at 10 kHz
    knob = KnobPhysics(p)
    d = np.array([0.0, 0.05, 0.05, 0.05, 0.05, 0.0])
    zero = np.zeros(6)
    torque = knob.run_block(CoefficientBlock(d, zero, zero)).torque
    np.testing.assert_allclose(torque, [0.0, 0.01, 0.02, 0.03, 0.04, 0.03], atol=1e-15)
    project = edits.new_project("time")
    project, track = edits.add_track(project, "drive", "drive")
    project, tile = edits.add_tile(project, generator("constant", 0.01, "step", value=1.0))
    project, _ = edits.add_clip(project, track, tile, 0.0, gain=0.5)  # 90 mNm in one period
    with open_device("sim", slew=100.0) as sim:
        assert sim.info.slew == 100.0
        (found,) = [f for f in check(project, sim.info).findings if f.kind == "slew-limit"]
    assert found.value == pytest.approx(900.0) and found.limit == 100.0
