"""What the knob's telemetry reports from the servo loop's record, compiled with numba.

From the true angle before each period, the motor torque and the Coulomb friction torque:
where the simulation blew up (the first period after which the angle is not finite or moved
faster than a limit), the encoder reading relative to the anchor, the firmware's filtered
velocity (backward difference through the first-order low-pass, in scipy.signal.lfilter's
direct form II transposed, so the numbers equal that filter's) and the cumulative energy the
device put in (motor work minus its viscous dissipation, integrated exactly by the servo loop,
and its Coulomb friction's). One call per block
instead of a dozen numpy calls: at 1,000 samples a block their per-call overhead cost more
than the servo loop itself.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit


# cache and error_model as for the servo loop (loop.py): no division here
@njit(cache=True, error_model="numpy")
def blow_up_index(thetas: np.ndarray, theta_end: float, rate: float, limit: float) -> int:
    """The first period after which the angle is not finite or its speed is beyond `limit`
    (rad/s); len(thetas) when there is none."""
    n = thetas.size
    for i in range(n):
        after = thetas[i + 1] if i + 1 < n else theta_end
        if not math.isfinite(after) or abs(after - thetas[i]) * rate > limit:
            return i
    return n


@njit(cache=True, error_model="numpy")
def readings(
    thetas: np.ndarray,
    theta_end: float,
    taus: np.ndarray,
    frictions: np.ndarray,
    losses: np.ndarray,
    encoder: tuple[float, float, float],
    velocity: tuple[float, float, float],
    energy0: float,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The reading, filtered velocity and cumulative energy after each period.

    losses: the viscous dissipation in each period (the servo loop integrates it exactly);
    encoder: quantum (0 = ideal), anchor, rate; velocity: the low-pass gain av, the reading
    and the velocity estimate before the first period; energy0: the energy before the first
    period.
    """
    quantum, anchor, rate = encoder
    av, prev_meas, vel = velocity
    n = thetas.size
    meas = np.empty(n)
    vels = np.empty(n)
    energy = np.empty(n)
    inv_q = 1.0 / quantum if quantum else 0.0
    a1 = av - 1.0  # lfilter's a = [1, av - 1], b = [av, 0]
    z = (1.0 - av) * vel
    total = 0.0
    for i in range(n):
        theta = thetas[i]
        reading = (np.floor(theta * inv_q + 0.5) * quantum if quantum else theta) - anchor
        raw = (reading - prev_meas) * rate
        y = z + av * raw
        z = raw * 0.0 - y * a1
        prev_meas = reading
        after = thetas[i + 1] if i + 1 < n else theta_end
        step = after - theta
        dissipated = losses[i] - frictions[i] * step
        work = taus[i] * step - dissipated
        total = work if i == 0 else total + work  # numpy's cumsum: no 0.0 + first term
        meas[i] = reading
        vels[i] = y
        energy[i] = energy0 + total
    return meas, vels, energy
