"""Rendered against designed: the clamp, the actuator and the knob's estimators, in numbers."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from tests.limits.designs import KNOB, layered, tone
from timeline.limits.actuators import actuator
from timeline.limits.design import sample
from timeline.limits.rendered import knob, vibration
from timeline.plugins.device_protocol import Hand


def test_the_clamp_cuts_a_drive_above_full_scale() -> None:
    shaker = replace(KNOB, kind="vibrotactile", max_output=1.0, dynamics=None)
    trace = vibration(sample(tone(175.0, 1.3), 1e4), shaker, None)
    assert np.abs(trace.designed).max() == pytest.approx(1.3, rel=1e-3)
    assert np.abs(trace.rendered).max() == 1.0
    assert trace.worst_gap() == pytest.approx(0.3, rel=1e-3)


def test_an_lra_renders_its_resonance_and_drops_a_low_tone() -> None:
    lra = actuator("lra-175")
    at = vibration(sample(tone(175.0, 0.1, 0.5), 1e4), KNOB, lra).rendered[-1000:]
    low = vibration(sample(tone(90.0, 0.1, 0.5), 1e4), KNOB, lra).rendered[-1000:]
    assert np.abs(at).max() == pytest.approx(0.1, rel=0.02)
    assert np.abs(low).max() == pytest.approx(0.1 * lra.gain(90.0), rel=0.1)


def test_a_saturating_drive_shows_on_the_knob() -> None:
    trace = knob(layered("drive", 0.25, seconds=0.05), KNOB, Hand("hold"))
    assert trace.worst_gap() == pytest.approx(0.07, rel=1e-6)  # 250 mNm asked, 180 applied
    assert trace.time.size == 500


def test_a_soft_spring_renders_as_drawn() -> None:
    trace = knob(layered("stiffness", 0.2, seconds=0.5), KNOB, Hand("turn", 90.0))
    assert np.abs(trace.designed).max() > 5e-3  # 0.2 N*m/rad over up to 45 deg
    assert trace.worst_gap() < 0.05 * np.abs(trace.designed).max()


def test_a_position_project_renders_against_the_angle_with_the_hand_turning_it() -> None:
    from timeline import edits, generator

    p = edits.new_project("position")
    p, track = edits.add_track(p, "torque")
    p = edits.set_track(p, track, full_scale=0.3)
    p, tile = edits.add_tile(p, generator("sine", np.pi / 2, "detents", frequency=8 / np.pi))
    p, _ = edits.add_clip(p, track, tile, 0.0)
    trace = knob(p, KNOB, Hand.parse("hold"))  # holding: turned at 90 deg/s to sweep the tables
    assert trace.axis == "position" and trace.label.endswith("hand turn:90")
    assert trace.designed.max() == pytest.approx(0.3, rel=0.02)
    assert np.abs(trace.rendered).max() == pytest.approx(0.18)  # the knob's clamp
    assert trace.angle.min() > -0.05 and trace.angle.max() > 1.0  # swept most of 0-90 degrees
    assert trace.step == pytest.approx(np.radians(0.01))  # the table's step
    inside = np.abs(trace.designed) < 0.1
    np.testing.assert_allclose(trace.rendered[inside], trace.designed[inside], atol=0.01)
    # a grasp's soft grip (0.054 N*m/rad) cannot drag the knob over a 0.18 N*m detent: it stalls
    stalled = knob(p, KNOB, Hand.parse("grasp"))
    assert stalled.label.endswith("hand grasp-turn:90")
    assert np.degrees(np.ptp(stalled.angle)) < 2.0
