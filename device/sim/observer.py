"""A tracking observer for the knob's velocity and acceleration (instead of filtered differences).

Each period the firmware predicts [theta, omega, alpha] over the period (kinematics, alpha held
constant) and corrects the prediction with the encoder reading (current-estimator form; the
gain L from Ackermann's formula puts all three poles at exp(-2*pi*bandwidth*T)). Velocity is the
estimated omega, acceleration the estimated alpha. It needs no knowledge of the rotor or the
hand. (A rotor-model observer with a disturbance state is exact on a free knob but, with a hand
holding the knob, must track the hand's inertia through 1/J and was 1.6x off at 175 Hz.)
"""

from __future__ import annotations

import math

import numpy as np

OFF = (0.0,) * 13  # the loop's observer tuple when the filters estimate instead


def kinematics(period: float) -> np.ndarray:
    """A over one period for [theta, omega, alpha] with alpha constant."""
    t = period
    return np.array([[1.0, t, t * t / 2.0], [0.0, 1.0, t], [0.0, 0.0, 1.0]])


def observer_gains(a: np.ndarray, pole: float) -> np.ndarray:
    """Current-estimator gain L placing every pole of (I - L C) A at `pole` (Ackermann)."""
    c = np.array([1.0, 0.0, 0.0])
    rows = np.array([c @ np.linalg.matrix_power(a, i) for i in (1, 2, 3)])
    shifted = a - pole * np.eye(3)
    return shifted @ shifted @ shifted @ np.linalg.solve(rows, np.array([0.0, 0.0, 1.0]))


def gains(period: float, bandwidth: float) -> np.ndarray:
    """L for the tracking observer at a bandwidth (Hz)."""
    return observer_gains(kinematics(period), math.exp(-2.0 * math.pi * bandwidth * period))


def observer_tuple(period: float, bandwidth: float) -> tuple[float, ...]:
    """What the compiled loop needs: on, A by rows, L."""
    return tuple(float(x) for x in (1.0, *kinematics(period).ravel(), *gains(period, bandwidth)))


def acceleration_response(period: float, bandwidth: float, frequency) -> np.ndarray:  # noqa: ANN001
    """Estimated over true acceleration at frequencies (Hz), ideal sensor, steady state."""
    a, l_gain = kinematics(period), gains(period, bandwidth)
    m = (np.eye(3) - np.outer(l_gain, [1.0, 0.0, 0.0])) @ a
    out = []
    for f in np.atleast_1d(np.asarray(frequency, dtype=np.float64)):
        w = 2.0 * np.pi * f
        state = np.linalg.solve(np.eye(3) - m / np.exp(1j * w * period), l_gain)
        out.append(state[2] / (1j * w) ** 2)
    return np.array(out)
