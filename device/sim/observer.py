"""Observers of the knob's angle, velocity and acceleration (instead of filtered differences).

Both observers run the same loop each period: predict [theta, omega, alpha] over the period with
the kinematic model (alpha held constant: the unknown torques of the hand and friction drive it)
and correct the prediction with the encoder reading (current-estimator form,
x = A x + L (reading - (A x)[0])). They differ in the gain L:

* `kalman` (the default estimator): the steady-state Kalman gain for that model, with the
  reading's noise the encoder's quantisation (sigma_theta = quantum/sqrt(12),
  docs/references.md) and the acceleration a random walk whose step per period is chosen from
  the same quantisation: the largest step for which the acceleration estimate's noise (white
  quantisation noise through the observer, computed from its matrices) is `noise` times the
  noise of a raw 3-point difference (docs/references.md: 1.23e3 rad/s^2 at the paper's
  encoder). Both covariances scale with the quantum, so L depends only on that fraction, and an
  ideal sensor gets the same firmware.
* `tracking`: all three poles of (I - L C) A at exp(-2*pi*bandwidth*T) (Ackermann's formula).

Neither needs the rotor or the hand. A rotor-model observer that feeds the commanded torque
forward (J alpha = tau + disturbance) is exact on a free knob, but a hand's inertia J_h on the
knob turns its acceleration estimate into alpha * (1 + (J_h/J) * (1 - H)), with H the
disturbance path's response (docs/devices.md): 1.66x at 175 Hz with the default grip, 12.3x
with a grasp; so the torque is not fed forward.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
from scipy.linalg import solve_discrete_are

OFF = (0.0,) * 13  # the loop's observer tuple when the filters estimate instead
C = np.array([1.0, 0.0, 0.0])
NOISE = 0.02  # the Kalman observer's acceleration noise, as a fraction of a raw 3-point estimate's


def kinematics(period: float) -> np.ndarray:
    """A over one period for [theta, omega, alpha] with alpha constant."""
    t = period
    return np.array([[1.0, t, t * t / 2.0], [0.0, 1.0, t], [0.0, 0.0, 1.0]])


def error_matrix(period: float, gains: np.ndarray) -> np.ndarray:
    """(I - L C) A: the map of the observer's state from period to period (reading aside)."""
    return (np.eye(3) - np.outer(gains, C)) @ kinematics(period)


def tracking_gains(period: float, bandwidth: float) -> np.ndarray:
    """L placing every pole of (I - L C) A at exp(-2*pi*bandwidth*T) (Ackermann)."""
    a = kinematics(period)
    pole = math.exp(-2.0 * math.pi * bandwidth * period)
    rows = np.array([C @ np.linalg.matrix_power(a, i) for i in (1, 2, 3)])
    shifted = a - pole * np.eye(3)
    return shifted @ shifted @ shifted @ np.linalg.solve(rows, np.array([0.0, 0.0, 1.0]))


def raw_acceleration_noise(period: float, sigma: float = 1.0) -> float:
    """RMS of a 3-point second difference of readings with white noise sigma (rad/s^2)."""
    return sigma * math.sqrt(6.0) / period**2


def acceleration_noise(period: float, gains: np.ndarray, sigma: float = 1.0) -> float:
    """RMS of the observer's acceleration estimate for white reading noise sigma (rad/s^2):
    sigma * sqrt(sum over k of ((M^k L)[2])^2), M = (I - L C) A, summed until it converges."""
    m, h, total = error_matrix(period, gains), np.asarray(gains, dtype=np.float64), 0.0
    for _ in range(100_000):
        total += h[2] * h[2]
        if h @ h < 1e-30 * max(total, 1e-300):
            break
        h = m @ h
    return sigma * math.sqrt(total)


def _kalman_gain(period: float, step: float, sigma: float) -> np.ndarray:
    """Steady-state current-estimator Kalman gain: reading variance sigma^2, acceleration
    random walk step `step` per period. Scaled to [theta, omega*T, alpha*T^2] for the solver."""
    scale = np.array([1.0, period, period * period])
    a = kinematics(period) * scale[:, None] / scale[None, :]
    q = np.diag([0.0, 0.0, (step * period * period) ** 2])
    p = solve_discrete_are(a.T, C[:, None], q, np.array([[sigma * sigma]]))
    return (p[:, 0] / (p[0, 0] + sigma * sigma)) / scale


@lru_cache(maxsize=32)
def _kalman_gains(period: float, noise: float) -> tuple[float, float, float]:
    sigma = 1.0  # L depends only on the ratio of the covariances; any quantum gives the same
    target = noise * raw_acceleration_noise(period, sigma)
    lo, hi = math.log(1e-6 * target), math.log(1e6 * target)  # step per period, rad/s^2

    def noisy(log_step: float) -> bool:
        return acceleration_noise(period, _kalman_gain(period, math.exp(log_step), sigma)) > target

    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if noisy(mid) else (mid, hi)
    return tuple(float(x) for x in _kalman_gain(period, math.exp(lo), sigma))


def kalman_gains(period: float, noise: float = NOISE) -> np.ndarray:
    """L of the steady-state Kalman observer whose acceleration noise is `noise` times a raw
    3-point estimate's (0 < noise < 1)."""
    if not 0.0 < noise < 1.0:
        raise ValueError(f"the observer's noise is a fraction between 0 and 1, not {noise}")
    return np.array(_kalman_gains(float(period), float(noise)))


def observer_tuple(period: float, gains: np.ndarray) -> tuple[float, ...]:
    """What the compiled loop needs: on, A by rows, L."""
    return tuple(float(x) for x in (1.0, *kinematics(period).ravel(), *gains))


def acceleration_response(period: float, gains: np.ndarray, frequency) -> np.ndarray:  # noqa: ANN001
    """Estimated over true acceleration at frequencies (Hz), ideal sensor, steady state."""
    m = error_matrix(period, gains)
    out = []
    for f in np.atleast_1d(np.asarray(frequency, dtype=np.float64)):
        w = 2.0 * np.pi * f
        state = np.linalg.solve(np.eye(3) - m / np.exp(1j * w * period), gains)
        out.append(state[2] / (1j * w) ** 2)
    return np.array(out)
