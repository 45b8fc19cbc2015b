"""The firmware's estimates against the true derivatives: the accuracy review's numbers."""

from __future__ import annotations

import numpy as np
import pytest

from device.sim import KnobParams, KnobPhysics, observer
from device.sim.bench.estimator import mass_noise
from device.sim.estimator import acceleration_response, velocity_response
from timeline.plugins.device_protocol import CoefficientBlock, DeviceError, Hand


def test_the_filter_at_175_hz_is_three_quarters_and_47_degrees_late() -> None:
    h = acceleration_response(KnobParams(estimator="filter"), 175.0)
    assert abs(h) == pytest.approx(0.7497, abs=1e-3)
    assert np.degrees(np.angle(h)) == pytest.approx(-46.9, abs=0.1)


def test_without_filters_the_estimates_are_the_backward_difference() -> None:
    raw = KnobParams(velocity_cutoff=0.0, acceleration_cutoff=0.0)
    w = 2 * np.pi * 100.0
    z = np.exp(1j * w * raw.period)
    assert velocity_response(raw, 100.0) == pytest.approx((1 - 1 / z) * raw.rate / (1j * w))
    assert abs(velocity_response(raw, 1.0)) == pytest.approx(1.0, abs=1e-6)


@pytest.mark.parametrize(
    ("estimator", "speed", "expected"),
    [("filter", 37.0, 0.63e-3), ("kalman", 37.0, 0.20e-3), ("filter", 90.0, 0.0),
     ("kalman", 90.0, 0.0)],
)  # fmt: skip
def test_mass_torque_noise_at_constant_speed(estimator: str, speed: float, expected: float) -> None:
    noise = mass_noise(speed, 1.0, estimator)
    if expected:  # 3.7 counts per period: the quantisation beats
        assert noise == pytest.approx(expected, rel=0.1)
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


@pytest.mark.parametrize(
    ("estimator", "frequency"), [("filter", 175.0), ("tracking", 175.0), ("kalman", 175.0),
                                 ("kalman", 50.0)]
)  # fmt: skip
def test_the_sim_follows_the_computed_response(estimator: str, frequency: float) -> None:
    p = KnobParams(estimator=estimator)
    expected = (
        acceleration_response(p, frequency)
        if estimator == "filter"
        else observer.acceleration_response(p.period, p.observer_gains, frequency)[0]
    )
    measured = _measured_acceleration_response(estimator, frequency)
    assert abs(measured) == pytest.approx(abs(expected), rel=0.01)
    assert np.angle(measured) == pytest.approx(np.angle(expected), abs=np.radians(0.5))


def test_the_tracking_observer_follows_175_hz_better_at_the_same_noise() -> None:
    h = observer.acceleration_response(1e-4, observer.tracking_gains(1e-4, 1000.0), 175.0)[0]
    assert abs(h) == pytest.approx(0.956, abs=1e-3)
    assert np.degrees(np.angle(h)) == pytest.approx(-27.6, abs=0.1)
    assert mass_noise(37.0, 1.0, "tracking") == pytest.approx(0.65e-3, rel=0.1)


def test_the_kalman_observer_is_the_default_and_beats_the_filter_on_gain_phase_and_noise() -> None:
    assert KnobParams().estimator == "kalman"
    kalman = observer.acceleration_response(1e-4, observer.kalman_gains(1e-4), 175.0)[0]
    old = acceleration_response(KnobParams(estimator="filter"), 175.0)
    assert abs(kalman) == pytest.approx(1.000, abs=1e-3)  # the filter: 0.750
    assert np.degrees(np.angle(kalman)) == pytest.approx(-31.5, abs=0.1)  # the filter: -46.9
    assert abs(1 - kalman) < 0.75 * abs(1 - old)  # the error as a vector: 0.54 against 0.73
    assert mass_noise(37.0, 1.0) < 0.35 * mass_noise(37.0, 1.0, "filter")


def test_the_kalman_gain_is_set_by_the_noise_budget_from_the_quantisation() -> None:
    sigma = np.radians(0.001) / np.sqrt(12.0)  # docs/references.md: 5.04e-6 rad
    raw = observer.raw_acceleration_noise(1e-4, sigma)
    assert raw == pytest.approx(1.23e3, rel=0.01)  # docs/references.md's 3-point figure
    for budget in (0.01, 0.02, 0.05):
        gains = observer.kalman_gains(1e-4, budget)
        assert observer.acceleration_noise(1e-4, gains, sigma) == pytest.approx(budget * raw)
    # a tighter budget is a slower observer: more lag at 175 Hz
    lags = [np.angle(observer.acceleration_response(1e-4, observer.kalman_gains(1e-4, b), 175.0))
            for b in (0.01, 0.02, 0.05)]  # fmt: skip
    assert lags[0] < lags[1] < lags[2] < 0


def test_the_computed_white_noise_matches_a_simulated_white_sequence() -> None:
    gains = observer.kalman_gains(1e-4)
    m = observer.error_matrix(1e-4, gains)
    noise = np.random.default_rng(5).normal(0.0, 1.0, 200_000)
    state, out = np.zeros(3), np.empty(noise.size)
    for i, v in enumerate(noise):  # the observer driven by the reading's noise alone
        state = m @ state + gains * v
        out[i] = state[2]
    assert out[1000:].std() == pytest.approx(observer.acceleration_noise(1e-4, gains), rel=0.02)


@pytest.mark.parametrize("noise", [0.0, 1.0, -0.1, float("nan")])
def test_a_noise_budget_outside_0_to_1_is_refused(noise: float) -> None:
    with pytest.raises(DeviceError, match="observer noise"):
        KnobParams(observer_noise=noise)
