"""Stability of stiffness, damping and mass together, with the hand on the knob (issue 20).

The flags' root test (the closed loop's characteristic polynomial, timeline/limits/servo.py) is
checked against two independent methods: the eigenvalues of the loop's state-space matrix
(servo.loop_matrix, built row by row from the firmware's steps) and the simulation itself.
"""

from __future__ import annotations

import numpy as np
import pytest

from device.sim import KnobParams, KnobPhysics, stability_flags, stable_stiffness
from device.sim.bench.loop_sweep import LINEAR, Tally, mixes, play, sweep
from tests.limits.designs import KNOB
from timeline import edits, generator
from timeline.limits import servo
from timeline.limits.check import check
from timeline.plugins.device_protocol import ESTIMATORS, CoefficientBlock, Dynamics, Hand


@pytest.mark.parametrize("estimator", ESTIMATORS)
@pytest.mark.parametrize("delay", [0, 1])
def test_the_root_test_agrees_with_the_loop_matrix_eigenvalues(estimator: str, delay: int) -> None:
    p = KnobParams(estimator=estimator, delay=delay)
    rows = mixes(p, 100, np.random.default_rng(7))
    rows[:10, 0] = 0.0  # no spring: the free knob's angle mode sits at z = 1
    k, b, m = rows.T
    loop = servo.whole_loop(p.dynamics, p.period, k, b, m)
    radius = [servo.spectral_radius(servo.loop_matrix(p.dynamics, p.period, *row)) for row in rows]
    unstable = np.array(radius) > servo.UNSTABLE
    assert unstable.any() and not unstable.all()  # both kinds are tested
    np.testing.assert_array_equal(loop.any, unstable)
    np.testing.assert_allclose(loop.radius[unstable], np.array(radius)[unstable], rtol=1e-9)


def test_no_unstable_mix_goes_unflagged_and_few_flagged_ones_are_stable() -> None:
    """Random (k, b, m), each inside its own limit, every estimator, delay and hand: simulated."""
    total = Tally()
    for t in sweep(count=5, seconds=1.0).values():
        for name in ("runs", "unstable", "flagged", "missed", "false_alarms"):
            setattr(total, name, getattr(total, name) + getattr(t, name))
    assert total.runs == 3 * 2 * 6 * 5
    assert total.unstable >= 10  # the sweep reaches the unstable mixes
    assert total.missed == 0
    assert total.false_alarms <= 0.05 * total.flagged


@pytest.mark.parametrize(
    ("estimator", "delay", "mix", "hands"),
    [
        ("filter", 0, (0.0, 0.1, 1e-4), ("free", "pinch")),
        ("kalman", 0, (1.5, 0.0, -5e-6), ("free", "pinch")),
        ("kalman", 1, (0.0, 0.05, 1.2e-5), ("free", "pinch")),
        ("kalman", 0, (0.0, 0.0, -9.5e-6), ("pinch",)),
    ],
)  # fmt: skip
def test_the_issues_mixes_are_flagged_with_the_hands_that_grow(
    estimator: str, delay: int, mix: tuple[float, float, float], hands: tuple[str, ...]
) -> None:
    """Each layer inside its own limit; flagged exactly for the hands whose run grows."""
    p = KnobParams(**LINEAR, estimator=estimator, delay=delay)
    k_top = servo.passive_stiffness(p.dynamics.damping, 0.0, p.period, delay)
    low, high = servo.mass_limits(p.dynamics, p.period)
    assert mix[0] <= k_top and mix[1] <= servo.damping_limit(p.dynamics, p.period)
    assert low <= mix[2] <= high
    for hand in (Hand("free"), Hand("hold"), Hand("hold", model="pinch")):
        flagged, unstable = play(p, hand, np.array(mix), 1.0)
        name = "pinch" if hand.model == "pinch" else hand.mode
        assert flagged == unstable == (name in hands), name


def test_the_shipped_knob_flags_damping_with_mass_that_saturates() -> None:
    """Damping 0.1 with mass 1e-4 on the filter estimator saturates the free knob (issue 20)."""
    knob = KnobPhysics(KnobParams(estimator="filter"))
    knob.start(Hand("free"))
    n = 5000
    d, zero = np.zeros(n), np.zeros(n)
    d[:5] = 1e-2
    tel = knob.run_block(CoefficientBlock(d, zero, np.full(n, 0.1), np.full(n, 1e-4)))
    assert tel.time_saturated > 0.05
    assert tel.flag("unstable-loop").count == n


def test_passivity_fires_with_damping_alone_beyond_the_device_damping() -> None:
    p = KnobParams()
    zero = np.zeros(3)
    damping = np.array([0.5, 1.0, 2.0]) * p.viscous  # |B| against b_dev = 1e-4
    flags = stability_flags(np.arange(3.0), zero, damping, None, p.dynamics, p.period)
    (passivity,) = [f for f in flags if f.kind == "passivity"]
    np.testing.assert_array_equal(passivity.times, [2.0])
    assert passivity.margins[0] == pytest.approx(p.viscous / (0.5 * p.period))


def test_stable_stiffness_honours_the_delay() -> None:
    """The closed form against the loop model's edge (bisection on its eigenvalues)."""
    assert stable_stiffness(1e-4, 3e-5, 1e-4, delay=1) == pytest.approx(0.8667, abs=1e-4)
    for delay in (0, 1):
        edge = servo.stable_stiffness(Dynamics(1e-5, 1.3e-4, delay), 1e-4)
        assert stable_stiffness(1e-4, 3e-5, 1e-4, delay) == pytest.approx(edge, rel=1e-3)


def _mix(b: float, m: float):  # noqa: ANN202 - a Project
    p = edits.new_project("time")
    for kind, value in (("damping", b), ("mass", m)):
        p, track = edits.add_track(p, kind, kind)
        p = edits.set_track(p, track, full_scale=abs(value))
        p, tile = edits.add_tile(p, generator("constant", 0.2, "level", value=1.0))
        p, _ = edits.add_clip(p, track, tile, 0.1, gain=1.0 if value > 0 else -1.0)
    return p


def test_check_finds_the_whole_loop_with_every_hand() -> None:
    """KNOB: the filter estimator; the pinch alone makes -9.5e-6 kg*m^2 unstable."""
    (found,) = check(_mix(0.1, 1e-4), KNOB).findings  # each inside: 0.5 and 0.56 of its limit
    assert found.kind == "unstable-loop" and "free knob" in found.what
    assert (found.start, found.stop) == pytest.approx((0.1, 0.3))
    assert found.value > 1.0 and found.limit == 1.0
    (pinched,) = check(_mix(1e-6, -9.5e-6), KNOB).findings
    assert "pinch hand holding" in pinched.what and "free knob" not in pinched.what
    assert check(_mix(1e-6, -5e-6), KNOB).findings == ()
