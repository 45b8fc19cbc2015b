"""The --hand specification: hold, free, turn:DEG_PER_S, push:MNM."""

from __future__ import annotations

import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

from timeline.plugins.device_protocol import Hand, HandSpecError

finite = st.floats(allow_nan=False, allow_infinity=False, min_value=-1e6, max_value=1e6)


@given(st.sampled_from(["turn", "push"]), finite)
def test_modes_with_a_value_round_trip(mode: str, value: float) -> None:
    hand = Hand.parse(f"{mode}:{value!r}")
    assert (hand.mode, hand.value) == (mode, value)
    assert Hand.parse(str(hand)).mode == mode


def test_units_and_defaults() -> None:
    assert Hand.parse("turn:90").turn_speed == pytest.approx(math.pi / 2)
    assert Hand.parse("push:50").push_torque == pytest.approx(0.05)
    assert Hand.parse(" HOLD ").mode == "hold" and Hand.parse("free").touches is False
    assert Hand.parse("turn").value == 90.0 and Hand.parse("push").value == 20.0


@given(st.text(max_size=20))
def test_anything_else_is_one_clear_error(text: str) -> None:
    try:
        hand = Hand.parse(text)
    except HandSpecError as exc:
        assert "\n" not in str(exc) and str(exc)
    else:
        assert hand.mode in ("hold", "turn", "push", "free")


@pytest.mark.parametrize(
    "text", ["spin", "turn:fast", "hold:3", "push:nan", "turn:inf", "", "turn:1:2"]
)
def test_bad_specs_are_refused(text: str) -> None:
    with pytest.raises(HandSpecError):
        Hand.parse(text)
