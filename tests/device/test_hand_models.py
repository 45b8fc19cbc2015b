"""Named hands (pinch, grasp): their numbers, their spec, their coupling in the simulated knob."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from device.sim import KnobParams, KnobPhysics
from timeline.plugins.device_protocol import HAND_MODELS, CoefficientBlock, Hand, HandSpecError

IDEAL = dict(quantum=0.0, coulomb=0.0, velocity_cutoff=0.0)  # the textbook sampled knob


def test_the_published_linear_values_are_rotated_at_the_stated_radius() -> None:
    grasp, pinch = HAND_MODELS["grasp"], HAND_MODELS["pinch"]
    # van Beek et al. 2015, Fig. 3f: 0.554 kg, 6.45 N*s/m, 135 N/m, held at 20 mm
    assert grasp.inertia == pytest.approx(0.554 * 0.02**2, rel=1e-12) == 2.216e-4
    assert grasp.damping == pytest.approx(2.58e-3) and grasp.stiffness == pytest.approx(0.054)
    # Fu & Cavusoglu 2012: k1 575 N/m, b1 1.3 N*s/m (midpoints), no finger mass, held at 15 mm
    assert pinch.stiffness == pytest.approx(0.129375) and pinch.damping == pytest.approx(2.925e-4)
    assert pinch.inertia == 0.0 and pinch.radius == 0.015
    assert all(m.source for m in HAND_MODELS.values())


@pytest.mark.parametrize(
    "text, shown, mode, value, model",
    [
        ("pinch", "pinch", "hold", 0.0, "pinch"),
        (" GRASP ", "grasp", "hold", 0.0, "grasp"),
        ("grasp-turn:45", "grasp-turn:45", "turn", 45.0, "grasp"),
        ("pinch - push:-10", "pinch-push:-10", "push", -10.0, "pinch"),
        ("pinch-turn", "pinch-turn:90", "turn", 90.0, "pinch"),
        ("default-free", "free", "free", 0.0, "default"),
    ],
)
def test_a_model_composes_with_every_mode(text, shown, mode, value, model) -> None:
    hand = Hand.parse(text)
    assert (str(hand), hand.mode, hand.value, hand.model) == (shown, mode, value, model)
    assert Hand.parse(str(hand)) == hand
    assert hand.grip_stiffness == HAND_MODELS[model].stiffness


@given(st.sampled_from(sorted(HAND_MODELS)), st.sampled_from(["hold", "free", "turn", "push"]))
def test_named_hands_round_trip_through_their_text(model: str, mode: str) -> None:
    hand = Hand(mode, 12.5 if mode in ("turn", "push") else 0.0, model=model)
    assert Hand.parse(str(hand)) == hand


@pytest.mark.parametrize("text", ["fist", "fist-hold", "pinch-", "pinch-hold:2", "-turn:3"])
def test_unknown_models_are_one_clear_sentence(text: str) -> None:
    with pytest.raises(HandSpecError) as err:
        Hand.parse(text)
    assert "\n" not in str(err.value) and str(err.value).endswith(")")


def test_a_named_model_sets_the_grip_whatever_was_passed() -> None:
    hand = Hand("hold", grip_stiffness=9.0, model="grasp")
    assert (hand.grip_stiffness, hand.inertia) == pytest.approx((0.054, 2.216e-4), rel=1e-12)
    with pytest.raises(HandSpecError):
        Hand("hold", model="fist")


def _step_response(hand: Hand, drive: float, seconds: float) -> tuple[np.ndarray, float]:
    p = KnobParams(**IDEAL)
    knob = KnobPhysics(p)
    knob.start(hand)
    n = round(seconds * p.rate)
    d = np.full(n, drive)
    tel = knob.run_block(CoefficientBlock(d, np.zeros(n), np.zeros(n)))
    return tel.angle, p.period


@pytest.mark.parametrize("name", ["pinch", "grasp"])
def test_the_knob_rings_at_the_hands_frequency_and_damping(name: str) -> None:
    """A 10 mNm step on the held knob: it settles at d/K and rings at sqrt(K/(J + J_hand)) with
    damping ratio (b_dev + B)/(2 sqrt(K (J + J_hand))), measured from the telemetry's angle."""
    model, p, drive = HAND_MODELS[name], KnobParams(**IDEAL), 0.01
    j = p.inertia + model.inertia
    wn = math.sqrt(model.stiffness / j)
    zeta = (p.viscous + model.damping) / (2 * math.sqrt(model.stiffness * j))
    angle, period = _step_response(Hand.parse(name), drive, 12 / (wn / (2 * math.pi)))
    rest = drive / model.stiffness
    x = angle - rest
    assert abs(x[-1]) < 1e-6 * rest  # settled at d/K
    up = np.flatnonzero((x[:-1] < 0) & (x[1:] >= 0))  # upward crossings of the rest angle
    t_up = (up + (-x[up]) / (x[up + 1] - x[up])) * period
    assert len(t_up) >= 2
    wd = 2 * math.pi / (t_up[1] - t_up[0])
    assert wd == pytest.approx(wn * math.sqrt(1 - zeta**2), rel=2e-3)
    overshoot = np.max(x) / rest  # first peak above the rest angle, as a fraction of it
    measured = -math.log(overshoot) / math.sqrt(math.pi**2 + math.log(overshoot) ** 2)
    assert measured == pytest.approx(zeta, rel=1e-2)
    expected = {"pinch": (18.1, 0.173), "grasp": (2.43, 0.379)}[name]  # Hz, zeta (docs table)
    assert (wn / (2 * math.pi), zeta) == pytest.approx(expected, rel=5e-3)
