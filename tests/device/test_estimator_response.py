"""The firmware's estimates against the true derivatives: the accuracy review's numbers."""

from __future__ import annotations

import numpy as np
import pytest

from device.sim import KnobParams, KnobPhysics, observer
from device.sim.estimator import acceleration_response, velocity_response
from timeline.bench.estimator import mass_noise
from timeline.devices import CoefficientBlock, Hand


def test_acceleration_at_175_hz_is_three_quarters_and_47_degrees_late() -> None:
    h = acceleration_response(KnobParams(), 175.0)
    assert abs(h) == pytest.approx(0.7497, abs=1e-3)
    assert np.degrees(np.angle(h)) == pytest.approx(-46.9, abs=0.1)


def test_without_filters_the_estimates_are_the_backward_difference() -> None:
    raw = KnobParams(velocity_cutoff=0.0, acceleration_cutoff=0.0)
    w = 2 * np.pi * 100.0
    z = np.exp(1j * w * raw.period)
    assert velocity_response(raw, 100.0) == pytest.approx((1 - 1 / z) * raw.rate / (1j * w))
    assert abs(velocity_response(raw, 1.0)) == pytest.approx(1.0, abs=1e-6)


@pytest.mark.parametrize(("speed", "noisy"), [(37.0, True), (90.0, False)])
def test_mass_torque_noise_at_constant_speed(speed: float, noisy: bool) -> None:
    noise = mass_noise(speed, 1.0)
    if noisy:  # 3.7 counts per period: the quantisation beats
        assert noise == pytest.approx(0.63e-3, rel=0.1)
    else:  # exactly 9 counts per period: the estimate is exact
        assert noise < 1e-9


def _measured_acceleration_response(estimator: str, frequency: float) -> complex:
    """Drive a held linear knob with a sine; fit the acceleration estimate against the truth."""
    p = KnobParams(quantum=0.0, coulomb=0.0, estimator=estimator)
    knob = KnobPhysics(p)
    knob.start(Hand("hold"))
    n = 4000
    t = np.arange(n) / p.rate
    drive = 0.01 * np.sin(2 * np.pi * frequency * t)
    tiny = 1e-9  # a mass too small to matter, so torque = drive - tiny * estimate
    zero = np.zeros(n)
    tel = knob.run_block(CoefficientBlock(drive, zero, zero, np.full(n, tiny)))
    estimate = (drive - tel.torque) / tiny
    true = np.gradient(np.gradient(tel.angle, 1 / p.rate), 1 / p.rate)
    keep = slice(n // 2, n - 2)
    basis = np.column_stack([np.sin(2 * np.pi * frequency * t[keep]),
                             np.cos(2 * np.pi * frequency * t[keep])])  # fmt: skip
    fit = [np.linalg.lstsq(basis, y[keep], rcond=None)[0] for y in (estimate, true)]
    return complex(*fit[0]) / complex(*fit[1])


@pytest.mark.parametrize("estimator", ["filter", "tracking"])
def test_the_sim_follows_the_computed_response(estimator: str) -> None:
    p = KnobParams(estimator=estimator)
    expected = (
        acceleration_response(p, 175.0)
        if estimator == "filter"
        else observer.acceleration_response(p.period, p.observer_bandwidth, 175.0)[0]
    )
    measured = _measured_acceleration_response(estimator, 175.0)
    assert abs(measured) == pytest.approx(abs(expected), rel=0.01)
    assert np.angle(measured) == pytest.approx(np.angle(expected), abs=np.radians(0.5))


def test_the_tracking_observer_follows_175_hz_better_at_the_same_noise() -> None:
    h = observer.acceleration_response(1e-4, 1000.0, 175.0)[0]
    assert abs(h) == pytest.approx(0.956, abs=1e-3)
    assert np.degrees(np.angle(h)) == pytest.approx(-27.6, abs=0.1)
    assert mass_noise(37.0, 1.0, "tracking") == pytest.approx(0.65e-3, rel=0.1)
