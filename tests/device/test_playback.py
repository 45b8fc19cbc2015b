"""Projects into device programs, and the fan knob felt through the simulated knob."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from device.sim import SimKnob
from timeline import edits
from timeline.files import projectfile
from timeline.plugins.device_protocol import Hand
from timeline.rendering.playback import coefficient_blocks, position_program, rest_angles
from timeline.tiles import generator

# The walls reach 0.8 x 180 mNm over their 20 degrees: the example keeps them below the
# delayed passivity bound (projects/build_examples.py).
WALL_TORQUE = 0.8 * 0.18

FAN = Path(__file__).resolve().parents[2] / "projects" / "fan_knob.htl"
REST_DEG = [50.0, 110.0, 170.0, 230.0]  # the example's Off, Lo, Med, Hi


def test_time_project_gives_blocks_with_absent_layers_zero_and_no_mass() -> None:
    p = edits.new_project("time")
    p, track = edits.add_track(p, "stiffness")
    p, tile = edits.add_tile(p, generator("constant", 0.25, value=0.5))
    p, _ = edits.add_clip(p, track, tile, 0.0)
    blocks, names = coefficient_blocks(p, 10_000.0)
    assert names == {"k": "stiffness"}
    assert sum(len(b) for b in blocks) == 2500
    assert all(b.m is None and not b.d.any() and not b.b.any() for b in blocks)
    np.testing.assert_allclose(np.concatenate([b.k for b in blocks]), 0.5)


@pytest.fixture(scope="module")
def fan():
    return projectfile.load(FAN)


def test_fan_knob_tables_have_four_rest_angles_between_the_walls(fan) -> None:
    program, names = position_program(fan)
    assert names == {"d": "torque", "b": "damping", "m": "mass"}
    np.testing.assert_allclose(np.degrees(rest_angles(program.table)), REST_DEG, atol=0.02)
    assert math.degrees(program.origin) == pytest.approx(50.0, abs=0.02)


@pytest.mark.parametrize("start_deg", [35.0, 95.0, 125.0, 185.0, 215.0, 245.0])
def test_a_released_fan_knob_settles_in_the_nearest_detent(fan, start_deg: float) -> None:
    program, _ = position_program(fan, 1.0, origin=math.radians(start_deg))
    tel = SimKnob().play(program, Hand("free"))
    final = math.degrees(program.origin + tel.angle[-1])
    nearest = min(REST_DEG, key=lambda r: abs(r - start_deg))
    assert final == pytest.approx(nearest, abs=0.5)  # Coulomb friction leaves a small dead band
    assert abs(tel.velocity[-500:]).max() < 0.05


def test_turning_through_the_range_feels_four_detents_and_the_wall(fan) -> None:
    hand = Hand("turn", 90.0)
    program, _ = position_program(fan, hand=hand)
    tel = SimKnob().play(program, hand)
    where = np.degrees(program.origin + tel.angle)
    bins = np.arange(52.0, 258.0, 1.0)  # 1-degree means smooth out encoder chatter
    which = np.digitize(where, bins)
    felt = np.array([tel.torque[which == i].mean() for i in range(1, bins.size)])
    centres = bins[:-1] + 0.5
    falling = centres[:-1][(felt[:-1] > 0) & (felt[1:] <= 0)] + 0.5  # restoring zero crossings
    np.testing.assert_allclose(falling, REST_DEG[1:], atol=1.5)  # Lo, Med, Hi after Off
    assert where.max() > 262 and tel.torque[-1] < -0.05  # the wall pushes back


@pytest.mark.parametrize(
    "push_mnm, expected_deg",
    [(100.0, 260 + 20 * 0.1 / WALL_TORQUE), (-100.0, 20 - 20 * 0.1 / WALL_TORQUE)],
)
def test_walls_stop_a_pushing_hand_where_torques_balance(
    fan, push_mnm: float, expected_deg: float
) -> None:
    hand = Hand("push", push_mnm)
    program, _ = position_program(fan, 3.0, hand=hand)  # 3 s: the walls' light damping rings
    tel = SimKnob().play(program, hand)
    final = math.degrees(program.origin + tel.angle[-1])
    assert final == pytest.approx(expected_deg, abs=1.0)
    assert abs(tel.velocity[-200:]).max() < 0.05
