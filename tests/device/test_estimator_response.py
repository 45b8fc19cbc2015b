"""The firmware's estimates against the true derivatives: the accuracy review's numbers."""

from __future__ import annotations

import numpy as np
import pytest

from device.sim import KnobParams
from device.sim.estimator import acceleration_response, velocity_response
from timeline.bench.estimator import mass_noise


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
