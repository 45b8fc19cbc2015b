"""Stability limits of a sampled knob's servo loop: stiffness, damping and virtual mass.

The loop a kinesthetic device runs each period T: read the encoder, estimate velocity (backward
difference, first-order low-pass) and acceleration (the difference of the velocity estimate,
low-passed, or an observer: predict with the acceleration held, correct with the reading, as the
device declares), compute tau = -k*theta - b*theta_dot - m*theta_ddot, apply it `delay` periods
later and hold it over a period on a rotor of inertia J and viscous damping b_dev. With an ideal
sensor and no friction that loop is linear, so its period-to-period map is a matrix and it is
stable exactly when every eigenvalue lies inside the unit circle (`spectral_radius` < 1). The
limits below are found on that map, with the knob free (no hand): a hand adds inertia and
damping and steadies the knob, so the free knob is the case to design for.

* stiffness: passivity (Colgate & Schenkel 1997): b_dev > K*T/2 + |B|; with a computation delay
  of D periods the held torque is older by D*T and the bound becomes b_dev > K*T*(1/2 + D) + |B|
  (the same energy-leak argument; Diolaiti et al. 2006 treat delay this way).
* damping: the largest B with the free knob's loop stable (about 2*J/T with a raw backward
  difference and no delay).
* mass: the band of m (negative to positive) with the loop stable; J + m <= 0 is never allowed.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
from scipy.linalg import expm

from timeline.errors import DeviceError
from timeline.plugins.device_protocol import Dynamics

UNSTABLE = 1.0 + 1e-9  # spectral radius above this grows; the free knob's angle mode sits at 1


def passive_stiffness(device_damping: float, virtual_damping, period: float, delay: int = 0):
    """K_pass = (b_dev - |B|) / (T*(1/2 + D)) in N*m/rad; scalars or arrays.

    An absurd virtual damping gives -inf (nothing is passive), which is the right answer.
    """
    with np.errstate(over="ignore"):
        return (device_damping - np.abs(virtual_damping)) / (period * (0.5 + delay))


def smoothing(cutoff: float, rate: float) -> float:
    """Gain of a first-order low-pass at a cut-off (1.0 = no filtering)."""
    return 1.0 if cutoff <= 0 else 1.0 - math.exp(-2.0 * math.pi * cutoff / rate)


def _plant(dynamics: Dynamics, period: float) -> np.ndarray:
    """The rotor's exact zero-order-hold map [theta, omega, u] -> [theta, omega] over a period."""
    a = np.zeros((3, 3))
    a[0, 1], a[1, 1], a[1, 2] = 1.0, -dynamics.damping / dynamics.inertia, 1.0 / dynamics.inertia
    return expm(a * period)[:2]


def _velocity_rows(dynamics: Dynamics, period: float, e: np.ndarray):  # noqa: ANN202
    """The next [meas, vel] over the loop's state [theta, omega, meas, vel, ...]: the backward
    difference of the reading through its low-pass."""
    rate = 1.0 / period
    av = smoothing(dynamics.velocity_cutoff, rate)
    return [e[0], (1.0 - av) * e[3] + av * rate * (e[0] - e[2])]


def _filter_rows(dynamics: Dynamics, period: float, e: np.ndarray, vel: np.ndarray):  # noqa: ANN202
    """The acceleration filter's next [prev_vel, acc] over the state [..., prev_vel, acc, ...]
    at 4 and 5 (the difference of the velocity estimate `vel`, low-passed)."""
    aa = smoothing(dynamics.acceleration_cutoff, 1.0 / period)
    return [vel, (1.0 - aa) * e[5] + aa * (vel - e[4]) / period]


def _observer_rows(dynamics: Dynamics, period: float, e: np.ndarray, vel: np.ndarray):  # noqa: ANN202, ARG001
    """The observer's next [angle, velocity, acceleration] over the state [..., o0, o1, o2, ...]
    at 4 to 6: predict with the acceleration held, correct by L times the reading's miss, as the
    firmware does."""
    t = period
    a = np.array([[1.0, t, t * t / 2.0], [0.0, 1.0, t], [0.0, 0.0, 1.0]])
    predicted = a @ e[4:7]
    miss = e[0] - predicted[0]
    return [predicted[i] + dynamics.observer_gains[i] * miss for i in range(3)]


def loop_matrix(
    dynamics: Dynamics, period: float, k: float = 0.0, b: float = 0.0, m: float = 0.0
) -> np.ndarray:
    """The free knob's closed loop over one period: state [theta, omega, meas, vel, the
    acceleration estimator's state (filter: prev_vel, acc; an observer: its angle, velocity and
    acceleration), tau(n-1) ... tau(n-D)]."""
    if not dynamics.estimator_declared:
        raise DeviceError("the servo loop cannot be modelled: the device does not declare its "
                          "velocity and acceleration estimator")  # fmt: skip
    observed = bool(dynamics.observer_gains)
    first_delay = 7 if observed else 6  # index of tau(n-1) in the state
    delay = int(dynamics.delay)
    e = np.eye(first_delay + delay)
    velocity = _velocity_rows(dynamics, period, e)
    acceleration = (_observer_rows if observed else _filter_rows)(dynamics, period, e, velocity[1])
    tau = -k * e[0] - b * velocity[1] - m * acceleration[-1]
    applied = e[first_delay + delay - 1] if delay else tau
    plant = _plant(dynamics, period)
    rows = [p[0] * e[0] + p[1] * e[1] + p[2] * applied for p in plant]
    rows += velocity + acceleration
    if delay:  # tau(n) is remembered, the older ones shift by one
        rows += [tau, *e[first_delay : first_delay + delay - 1]]
    return np.array(rows)


def spectral_radius(matrix: np.ndarray) -> float:
    """Largest eigenvalue magnitude (above 1: the loop grows)."""
    return float(np.abs(np.linalg.eigvals(matrix)).max())


def _edge(dynamics: Dynamics, period: float, layer: str, sign: float) -> float:
    """The magnitude of k, b or m (with the others zero) at which the loop turns unstable."""

    def stable(x: float) -> bool:
        return spectral_radius(loop_matrix(dynamics, period, **{layer: sign * x})) <= UNSTABLE

    scale = {"k": 1.0, "b": dynamics.inertia / period, "m": dynamics.inertia}[layer]
    if sign < 0 and layer == "m":
        hi = dynamics.inertia  # J + m <= 0 is never stable
    else:
        hi = scale
        while stable(hi):
            hi *= 2.0
            if hi > 1e12 * scale:
                return math.inf
    lo = 0.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if stable(mid) else (lo, mid)
    return lo


@lru_cache(maxsize=64)
def damping_limit(dynamics: Dynamics, period: float) -> float:
    """Largest virtual damping B (N*m*s/rad) the free knob's loop renders stably."""
    return _edge(dynamics, period, "b", 1.0)


@lru_cache(maxsize=64)
def mass_limits(dynamics: Dynamics, period: float) -> tuple[float, float]:
    """(lowest, highest) virtual mass m (kg*m^2) the free knob's loop renders stably."""
    return -_edge(dynamics, period, "m", -1.0), _edge(dynamics, period, "m", 1.0)


@lru_cache(maxsize=64)
def stable_stiffness(dynamics: Dynamics, period: float) -> float:
    """Largest stiffness K (N*m/rad) with the free knob's loop stable (B = m = 0)."""
    return _edge(dynamics, period, "k", 1.0)
