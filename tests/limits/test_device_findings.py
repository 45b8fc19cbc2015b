"""Each device finding at, just below and just above its limit."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from tests.limits.designs import KNOB, layered, tone
from timeline import edits, generator
from timeline.limits import servo
from timeline.limits.actuators import actuator
from timeline.limits.check import check

JUST = 1e-6  # relative step either side of a limit


def kinds(project, info=KNOB, chosen=None) -> list[str]:
    return [f.kind for f in check(project, info, chosen).findings]


@pytest.mark.parametrize(("scale", "found"), [(1 - JUST, False), (1.0, False), (1 + JUST, True)])
def test_torque_saturation(scale: float, found: bool) -> None:
    report = check(layered("drive", 0.18 * scale), KNOB)
    assert ("torque-saturation" in report.kinds()) == found
    if found:
        (f,) = report.findings
        assert f.value == pytest.approx(0.18 * scale) and f.limit == 0.18
        assert (f.start, f.stop) == pytest.approx((0.0, 0.2))
        assert "scale that part by 1.00" in f.advice


def test_saturation_on_a_position_table_is_an_angle_range() -> None:
    p = edits.new_project("position")
    p, track = edits.add_track(p, "torque", "torque")
    p = edits.set_track(p, track, full_scale=0.2)
    p, tile = edits.add_tile(p, generator("constant", 0.5, "level", value=1.0))
    p, _ = edits.add_clip(p, track, tile, 0.25)
    (f,) = check(p, KNOB).findings
    assert f.kind == "torque-saturation" and f.axis == "position"
    assert (f.start, f.stop) == pytest.approx((0.25, 0.75), abs=2 / p.rate)
    assert f.where() == "14.3 to 43.0 deg"


@pytest.mark.parametrize(("scale", "found"), [(1 - JUST, False), (1.0, False), (1 + JUST, True)])
def test_stiffness_limit(scale: float, found: bool) -> None:
    assert ("stiffness-limit" in kinds(layered("stiffness", 2.0 * scale))) == found


def test_stiffness_on_a_position_table_is_its_slope() -> None:
    p = edits.new_project("position")
    p, track = edits.add_track(p, "torque", "torque")
    p = edits.set_track(p, track, full_scale=0.1)
    p, tile = edits.add_tile(p, generator("ramp", 0.04, "wall", start=0.0, end=-1.0))
    p, _ = edits.add_clip(p, track, tile, 0.1)  # slope 2.5 N*m/rad > 2.0
    (f,) = check(p, KNOB).findings
    assert f.kind == "stiffness-limit" and f.value == pytest.approx(2.5, rel=1e-3)


@pytest.mark.parametrize(("scale", "found"), [(1 - JUST, False), (1.0, False), (1 + JUST, True)])
def test_damping_limit(scale: float, found: bool) -> None:
    limit = servo.damping_limit(KNOB.dynamics, KNOB.period)
    assert ("damping-limit" in kinds(layered("damping", limit * scale))) == found


def test_negative_damping() -> None:
    assert kinds(layered("damping", -1e-6)) == ["negative-damping"]
    assert kinds(layered("damping", 1e-6)) == []


@pytest.mark.parametrize(("scale", "found"), [(1 - JUST, False), (1.0, False), (1 + JUST, True)])
def test_mass_limit(scale: float, found: bool) -> None:
    high = servo.mass_limits(KNOB.dynamics, KNOB.period)[1]
    assert ("mass-limit" in kinds(layered("mass", high * scale))) == found


@pytest.mark.parametrize(("scale", "found"), [(1 - JUST, False), (1.0, True), (1 + JUST, True)])
def test_mass_cancelling_the_inertia(scale: float, found: bool) -> None:
    assert ("mass-cancels-inertia" in kinds(layered("mass", -1e-5 * scale))) == found


@pytest.mark.parametrize(("scale", "found"), [(1 - 1e-3, False), (1 + 1e-3, True)])
def test_slew_limit(scale: float, found: bool) -> None:
    info = replace(KNOB, slew=9.0)  # N*m per second
    p = edits.new_project("time")
    p, track = edits.add_track(p, "drive", "drive")
    p = edits.set_track(p, track, full_scale=0.09 * scale)
    p, tile = edits.add_tile(p, generator("ramp", 0.01, "edge", start=0.0, end=1.0))
    p, _ = edits.add_clip(p, track, tile, 0.0)  # 0 to 0.09*scale N*m in 10 ms: 9*scale N*m/s
    report = check(p, info)
    slews = [f for f in report.findings if f.kind == "slew-limit"]
    assert bool(slews) == found
    if found:
        assert slews[0].value == pytest.approx(9.0 * scale, rel=2e-3)


def _loss_frequency(lra, loss_db: float) -> float:
    """The frequency above resonance where the LRA's response is loss_db down."""
    lo, hi = lra.resonance, 4 * lra.resonance
    for _ in range(80):
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if -20 * np.log10(lra.gain(mid)) < loss_db else (lo, mid)
    return lo


@pytest.mark.parametrize(("loss", "found"), [(1.8, False), (2.6, True), (12.0, True)])
def test_energy_outside_an_lra_band(loss: float, found: bool) -> None:
    lra = actuator("lra-175")
    f = _loss_frequency(lra, loss)
    report = check(tone(f, 0.1, seconds=0.5), KNOB, lra)
    band = [x for x in report.findings if x.kind == "outside-actuator-band"]
    assert bool(band) == found
    if found:
        assert band[0].value == pytest.approx(loss, abs=0.3)
        assert band[0].stop - band[0].start > 0.4


def test_a_wideband_voice_coil_renders_what_an_lra_cannot() -> None:
    design = tone(90.0, 0.1, seconds=0.5)
    assert "outside-actuator-band" in kinds(design, chosen=actuator("lra-175"))
    assert "outside-actuator-band" not in kinds(design, chosen=actuator("voice-coil"))


def test_an_oscillating_layer_is_one_finding_per_stretch_not_per_half_cycle() -> None:
    p = edits.new_project("time")
    p, track = edits.add_track(p, "damping", "damping")
    p, tile = edits.add_tile(p, generator("sine", 0.15, "wobble", frequency=40.0))
    p, _ = edits.add_clip(p, track, tile, 0.0)
    p, _ = edits.add_clip(p, track, tile, 0.5)  # 0.35 s later: its own finding
    found = [f for f in check(p, KNOB).findings if f.kind == "negative-damping"]
    assert len(found) == 2  # 6 negative half cycles each
    assert found[0].start == pytest.approx(0.0125, abs=2e-4)
    assert found[0].stop == pytest.approx(0.15, abs=2e-4)
