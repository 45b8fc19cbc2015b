"""The knob's servo loop, one iteration per servo period, compiled with numba.

The loop carries this state from period to period and, through `KnobPhysics`, from block to
block (`State`, in this order):

* theta, omega: the rotor's true angle (rad) and speed (rad/s);
* grip: the hand's target angle (rad), moving at the turning hand's speed;
* anchor: the quantised angle when the play started (the firmware's zero);
* prev_meas: the last encoder reading relative to the anchor;
* vel: the low-passed backward-difference velocity estimate;
* prev_vel, acc: the previous velocity estimate and the low-passed acceleration estimate
  (updated only when the project has a mass layer);
* pending: the torque computed in the last period, applied in this one when the firmware has a
  one-period computation delay;
* est_theta, est_vel: an observer's angle and velocity estimates (used only when an observer
  estimates the acceleration; then acc is its acceleration estimate, observer.py);
* applied: the motor torque applied in the last period.

Each period: read the quantised encoder, update the velocity filter and (with a mass layer) the
acceleration estimate (filtered difference, or an observer's prediction corrected by the
reading), compute tau = d - k*theta -
b*theta_dot - m*theta_ddot (coefficients per period, or T, B, M looked up linearly at the angle
with k = 0), scale it by the watchdog's gain, clamp it (NaN becomes 0); with a computation
delay apply the torque computed one period earlier instead (it arrives a period late, as on
firmware that computes during a period and writes the amplifier at the next tick); limit its
change per period to the slew limit if there is one; add the hand's push,
add Coulomb friction as the torque (within its level) that would stop the rotor in the period,
and advance the mechanics by the plant's linear map (plant.py, its theta and omega rows).
"""

from __future__ import annotations

import numpy as np
from numba import njit

State = tuple[float, float, float, float, float, float, float, float, float, float, float, float]


# cache: compiled once per machine (and source change); error_model="numpy": IEEE division, no
# ZeroDivisionError checks inside the loop (its divisors, quantum and w2 and the push ramp, are
# tested or positive before it divides)
@njit(cache=True, error_model="numpy")
def servo_loop(
    coeffs: np.ndarray,
    tables: np.ndarray,
    gain: np.ndarray,
    use_mass: bool,
    lookup: tuple[float, float, float],
    firmware: tuple[float, float, float, float, float, float, float, float, float],
    plant: tuple[float, float, float, float, float, float, float, float, float, float],
    hand: tuple[float, float, float, float],
    state: State,
    observer: tuple[float, ...],
    loss: np.ndarray,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, int, State]:
    """Run len(gain) servo periods; return the true angle before each period, the motor torque,
    the Coulomb friction torque, the energy the rotor's viscous damping dissipated in each
    period, the count of NaN torques replaced by 0, and the new state.

    coeffs: rows d, k, b, m, one value per period (time projects; m is read only with use_mass);
    tables: rows T, B, M over angle (position projects; no columns in time projects), looked up
    at origin + angle, sample j at table angle start + j/rate, `lookup` = (origin, start, rate);
    firmware: rate, period, quantum, max torque, Coulomb level, velocity and acceleration filter
    gains, computation delay (0 or 1 period), slew limit (N*m/s, 0 = none); plant: the theta
    row then the omega row of the map over z = [theta, omega, u, r, v];
    hand: push torque, push ramp, turning speed, seconds since the play started; observer: on
    (1.0: it estimates the acceleration instead of the filter) or off (0.0), then the
    kinematic model's 3x3 matrix A by rows and the gains L (observer.py); loss: the 5x5 matrix
    W with z^T W z the viscous loss over a period from z = [theta, omega, u, r, v]
    (plant.viscous_loss: the exact integral of b_dev*omega(t)^2 over the held period).
    """
    rate, period, quantum, tmax, coulomb, av, aa, delay, slew = firmware
    t0, t1, t2, t3, t4, w0, w1, w2, w3, w4 = plant
    push, push_ramp, speed, elapsed = hand
    (theta, omega, r, anchor, prev_meas, vel, prev_vel, acc, pending,
     est_theta, est_vel, applied) = state  # fmt: skip
    observe = observer[0] != 0.0
    a00, a01, a02, a10, a11, a12, a20, a21, a22 = observer[1:10]
    l0, l1, l2 = observer[10:13]
    origin, tstart, trate = lookup
    in_table = tables.shape[1] > 0
    tlast = tables.shape[1] - 1
    inv_q = 1.0 / quantum if quantum else 0.0
    n = gain.size
    thetas = np.empty(n)
    taus = np.empty(n)
    frictions = np.zeros(n)
    losses = np.empty(n)
    nonfinite = 0
    d = k = b = m = 0.0
    for i in range(n):
        meas = ((theta * inv_q + 0.5) // 1.0 * quantum if quantum else theta) - anchor
        vel += av * ((meas - prev_meas) * rate - vel)
        if use_mass:
            if observe:  # predict with the model, correct with the reading (observer.py)
                p0 = a00 * est_theta + a01 * est_vel + a02 * acc
                p1 = a10 * est_theta + a11 * est_vel + a12 * acc
                p2 = a20 * est_theta + a21 * est_vel + a22 * acc
                miss = meas - p0
                est_theta = p0 + l0 * miss
                est_vel = p1 + l1 * miss
                acc = p2 + l2 * miss
            else:
                acc += aa * ((vel - prev_vel) * rate - acc)
                prev_vel = vel
        prev_meas = meas
        if in_table:  # T(theta) - B(theta)*theta_dot - M(theta)*theta_ddot, linear lookup
            x = (origin + meas - tstart) * trate
            j = tlast if x >= tlast else (int(x) if x > 0.0 else 0)  # NaN reads sample 0
            f = x - j if 0.0 < x < tlast else 0.0
            nxt = j + 1 if j < tlast else j
            d = tables[0, j] + f * (tables[0, nxt] - tables[0, j])
            b = tables[1, j] + f * (tables[1, nxt] - tables[1, j])
            if use_mass:
                m = tables[2, j] + f * (tables[2, nxt] - tables[2, j])
        else:
            d, k, b = coeffs[0, i], coeffs[1, i], coeffs[2, i]
            if use_mass:
                m = coeffs[3, i]
        tau = (d - k * meas - b * vel - m * acc) * gain[i]
        if tau > tmax:
            tau = tmax
        elif tau < -tmax:
            tau = -tmax
        elif tau != tau:
            tau = 0.0
            nonfinite += 1
        if delay:
            tau, pending = pending, tau
        if slew:  # the amplifier follows at most slew N*m/s
            step = slew * period
            if tau > applied + step:
                tau = applied + step
            elif tau < applied - step:
                tau = applied - step
        applied = tau
        u = tau
        if push:
            u += push if elapsed >= push_ramp else push * elapsed / push_ramp
            elapsed += period
        free = w0 * theta + w1 * omega + w2 * u + w3 * r + w4 * speed
        if coulomb:
            fr = -free / w2  # the friction torque that would stop the knob in this period
            fr = coulomb if fr > coulomb else (-coulomb if fr < -coulomb else fr)
            u += fr
            free += w2 * fr
            frictions[i] = fr
        thetas[i] = theta
        taus[i] = tau
        z = (theta, omega, u, r, speed)
        lost = 0.0
        for a in range(5):
            row = 0.0
            for c in range(5):
                row += loss[a, c] * z[c]
            lost += z[a] * row
        losses[i] = lost
        theta = t0 * theta + t1 * omega + t2 * u + t3 * r + t4 * speed
        omega = free
        r += speed * period
    return (
        thetas,
        taus,
        frictions,
        losses,
        nonfinite,
        (
            theta,
            omega,
            r,
            anchor,
            prev_meas,
            vel,
            prev_vel,
            acc,
            pending,
            est_theta,
            est_vel,
            applied,
        ),
    )
