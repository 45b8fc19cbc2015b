"""The simulated knob: exact mechanics, firmware-style sensing, clamp, NaN, watchdog, hand."""

from __future__ import annotations

import math

import numpy as np
import pytest

from device.sim import KnobParams, KnobPhysics, SimKnob
from timeline.plugins.device_protocol import (
    CoefficientBlock,
    DeviceError,
    Hand,
    PositionTable,
    open_device,
)

IDEAL = dict(quantum=0.0, coulomb=0.0, velocity_cutoff=0.0)  # the textbook sampled knob


def block(n: int, d=0.0, k=0.0, b=0.0, m=None) -> CoefficientBlock:
    full = lambda v: np.broadcast_to(np.asarray(v, dtype=float), (n,)).copy()  # noqa: E731
    return CoefficientBlock(full(d), full(k), full(b), None if m is None else full(m))


def test_constant_drive_matches_the_exact_rotor_response() -> None:
    """J*w' = d - b*w from rest: theta = (d/b)*(t - (J/b)*(1 - exp(-b t/J))), to 1e-9 relative."""
    p = KnobParams(**IDEAL)
    knob = KnobPhysics(p)
    knob.start(Hand("free"))
    tel = knob.run_block(block(2000, d=0.01))
    t = tel.time + p.period  # angle[i] is read at the start of period i; compare the next one
    tau_b = p.inertia / p.viscous
    exact = (0.01 / p.viscous) * (t - tau_b * (1 - np.exp(-t / tau_b)))
    measured = np.append(tel.angle[1:], knob.theta - knob.anchor)
    assert np.max(np.abs(measured - exact)) < 1e-9 * np.max(exact)


@pytest.mark.parametrize("integrator, tolerance", [("rk4", 1e-9), ("semi-implicit", 1e-2)])
def test_stepping_integrators_approach_the_exact_one(integrator: str, tolerance: float) -> None:
    runs = {}
    for name in ("zoh", integrator):
        knob = KnobPhysics(KnobParams(**IDEAL), integrator=name)
        knob.start(Hand("hold"))
        runs[name] = knob.run_block(block(3000, d=0.05, k=0.5, b=2e-5)).angle
    scale = np.max(np.abs(runs["zoh"]))
    assert np.max(np.abs(runs[integrator] - runs["zoh"])) < tolerance * scale


def test_sampled_spring_converges_to_the_continuous_one_at_first_order() -> None:
    """J th'' + (b_dev + B) th' + K th = d: the sampled knob's error shrinks ~10x per 10x rate."""
    k, b, d, duration = 1.0, 2e-4, 0.02, 0.05
    errors = []
    for rate in (10_000.0, 100_000.0):
        p = KnobParams(rate=rate, **IDEAL)
        knob = KnobPhysics(p)
        knob.start(Hand("free"))
        tel = knob.run_block(block(int(duration * rate), d=d, k=k, b=b))
        j, c = p.inertia, p.viscous + b
        wn, zeta = math.sqrt(k / j), c / (2 * math.sqrt(k * j))
        wd = wn * math.sqrt(1 - zeta**2)
        t = tel.time
        exact = (
            d
            / k
            * (1 - np.exp(-zeta * wn * t) * (np.cos(wd * t) + zeta * wn / wd * np.sin(wd * t)))
        )
        errors.append(np.max(np.abs(tel.angle - exact)) / (d / k))
    assert errors[0] < 0.1  # 10 kHz: within 10 % of the step size over 16 lightly damped cycles
    assert 6 < errors[0] / errors[1] < 14


def test_angle_is_quantised_to_encoder_counts_from_the_anchor() -> None:
    knob = KnobPhysics()
    knob.theta = 0.123456  # the knob rests somewhere; the play anchors there
    knob.start(Hand("free"))
    tel = knob.run_block(block(500, d=0.01))
    counts = tel.angle / knob.params.quantum
    assert tel.angle[0] == 0.0
    np.testing.assert_allclose(counts, np.round(counts), atol=1e-6)
    assert tel.angle[-1] > 100 * knob.params.quantum


def test_torque_is_clamped_and_saturation_is_timed() -> None:
    knob = KnobPhysics()
    knob.start(Hand("hold"))
    tel = knob.run_block(block(1000, d=1.0))
    assert tel.peak_torque == pytest.approx(0.18)
    assert tel.time_saturated == pytest.approx(0.1)


def test_non_finite_coefficients_never_reach_the_motor() -> None:
    d = np.full(100, 0.01)
    d[10:20] = np.nan
    k = np.zeros(100)
    k[30] = np.inf
    tel = SimKnob().play([CoefficientBlock(d, k, np.zeros(100))], Hand("hold"))
    assert np.isfinite(tel.torque).all() and np.isfinite(tel.angle).all()
    assert (tel.torque[10:20] == 0).all()  # a non-finite coefficient counts as 0
    assert tel.torque[30] == pytest.approx(0.01)
    flag = tel.flag("non-finite")  # played as zero, but never silently
    assert flag.count == 11 and flag.first_time == pytest.approx(tel.time[10])
    assert np.allclose(flag.times, tel.time[[*range(10, 20), 30]])
    assert "11 sample(s) held NaN or infinite coefficients (first: d = nan" in tel.warnings[0]
    big = KnobPhysics()
    big.start(Hand("free"))
    tel = big.run_block(block(50, d=1e308, k=-1e308, b=1e308))
    assert np.isfinite(tel.torque).all() and np.abs(tel.torque).max() <= 0.18


def test_a_position_table_with_nan_is_refused_not_zeroed() -> None:
    torque = np.linspace(-0.01, 0.01, 50)
    torque[7] = np.nan
    with pytest.raises(DeviceError, match="torque at sample 7 is nan, not a finite number"):
        PositionTable(0.0, 100.0, torque)
    damping = np.zeros(50)
    damping[3] = -np.inf
    with pytest.raises(DeviceError, match="damping at sample 3 is -inf"):
        PositionTable(0.0, 100.0, np.zeros(50), damping)


def test_watchdog_ramps_torque_to_zero_within_the_stated_time() -> None:
    p = KnobParams()
    knob = KnobPhysics(p)
    knob.start(Hand("hold"))
    knob.run_block(block(100, d=0.1))
    idle = knob.run_idle(300)
    t = idle.time - idle.time[0]
    bound = p.watchdog_timeout + p.watchdog_ramp
    assert np.abs(idle.torque[t < p.watchdog_timeout - 1e-9]).min() == pytest.approx(0.1)
    assert (idle.torque[t >= bound - 1e-9] == 0.0).all()
    assert np.all(np.diff(np.abs(idle.torque)) <= 1e-12)


def test_blocks_continue_one_run_exactly() -> None:
    whole, split = KnobPhysics(), KnobPhysics()
    for knob in (whole, split):
        knob.start(Hand("turn", 45.0))
    d = 0.02 * np.sin(np.arange(2000) / 50)
    k = np.full(2000, 0.3)
    b = np.full(2000, 5e-5)
    one = whole.run_block(CoefficientBlock(d, k, b))
    halves = [
        split.run_block(CoefficientBlock(d[s], k[s], b[s]))
        for s in (slice(0, 700), slice(700, None))
    ]
    np.testing.assert_array_equal(one.torque, np.concatenate([h.torque for h in halves]))
    np.testing.assert_array_equal(one.angle, np.concatenate([h.angle for h in halves]))


def test_a_push_against_a_spring_rests_where_torques_balance() -> None:
    """Push 20 mNm against k = 0.5 N*m/rad: rest at 0.04 rad within the friction dead band."""
    knob = KnobPhysics()
    knob.start(Hand("push", 20.0))
    tel = knob.run_block(block(20_000, k=0.5, b=5e-5))
    dead_band = knob.params.coulomb / 0.5
    assert abs(tel.angle[-1] - 0.04) <= dead_band + 1e-4
    assert abs(tel.velocity[-1000:]).max() < 1e-2


def test_a_turning_hand_turns_a_free_knob_at_its_speed() -> None:
    knob = KnobPhysics()
    knob.start(Hand("turn", 90.0))
    tel = knob.run_block(block(10_000))
    assert math.degrees(tel.angle[-1]) == pytest.approx(90.0, abs=1.0)
    assert math.degrees(np.median(tel.velocity[5000:])) == pytest.approx(90.0, rel=0.02)


def test_a_held_knob_stays_near_its_anchor_under_a_push() -> None:
    knob = KnobPhysics()
    knob.start(Hand("hold"))
    tel = knob.run_block(block(5000, d=0.05))
    assert abs(tel.angle[-1]) == pytest.approx(0.05 / Hand().grip_stiffness, rel=0.05)


def test_mass_layer_adds_inertia_only_when_present() -> None:
    """No mass layer and a zero mass layer render alike; m = 2J behaves like a 3J rotor."""
    p = KnobParams(**IDEAL)
    runs = []
    for m in (None, 0.0, 2 * p.inertia):
        knob = KnobPhysics(p)
        knob.start(Hand("free"))
        runs.append(knob.run_block(block(1000, d=0.01, m=m)).angle)
    np.testing.assert_array_equal(runs[0], runs[1])
    t, tau_b = 0.0999, 3 * p.inertia / p.viscous
    heavy = (0.01 / p.viscous) * (t - tau_b * (1 - math.exp(-t / tau_b)))
    assert runs[2][-1] == pytest.approx(heavy, rel=0.05)  # the estimate's filter lags a little


def test_device_declares_the_papers_knob_and_plays_through_open_device() -> None:
    with open_device("sim") as dev:
        info = dev.info
        tel = dev.play([block(100, d=0.01)] * 3)
    assert (info.kind, info.rate, info.max_output) == ("kinesthetic", 10_000.0, 0.18)
    assert info.resolution == pytest.approx(math.radians(0.001))
    assert len(tel) == 300 and tel.time[-1] == pytest.approx(0.0299)


def test_unknown_integrator_is_refused() -> None:
    with pytest.raises(DeviceError, match="unknown integrator"):
        KnobPhysics(integrator="leapfrog")
