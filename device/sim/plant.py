"""One servo period of the knob's mechanics as a linear map (exact, or a stepping scheme).

Between two servo samples the motor torque is held (zero-order hold). With the hand's grip a
spring-damper to a target angle moving at a constant speed, the mechanics

    (J + J_hand) * omega' = u - b_dev*omega - K_grip*(theta - r) - B_grip*(omega - v),  r' = v

are linear in the augmented state z = [theta, omega, u, r, v], so every integrator is a matrix:
exact (matrix exponential), semi-implicit Euler, explicit Euler or RK4, with substeps.
"""

from __future__ import annotations

import numpy as np
from scipy.linalg import expm

from timeline.plugins.device_protocol import DeviceError, Hand

INTEGRATORS = ("zoh", "rk4", "semi-implicit", "euler")


def system_matrix(inertia: float, damping: float, grip_k: float, grip_b: float) -> np.ndarray:
    """The continuous augmented system z' = A z for z = [theta, omega, u, r, v]."""
    a = np.zeros((5, 5))
    a[0, 1] = 1.0
    a[1] = [-grip_k, -(damping + grip_b), 1.0, grip_k, grip_b]
    a[1] /= inertia
    a[3, 4] = 1.0
    return a


def held_plant(
    inertia: float, damping: float, hand: Hand
) -> tuple[tuple[float, float, float], np.ndarray]:
    """The rotor with this hand on it: its key (inertia, grip stiffness, grip damping), by which
    callers cache its maps, and its system matrix."""
    inertia += hand.inertia if hand.touches else 0.0
    grip_k, grip_b = (hand.grip_stiffness, hand.grip_damping) if hand.grips else (0.0, 0.0)
    return (inertia, grip_k, grip_b), system_matrix(inertia, damping, grip_k, grip_b)


def step_matrix(a: np.ndarray, h: float, integrator: str = "zoh", substeps: int = 1) -> np.ndarray:
    """The map z(t) -> z(t + h) of an integrator taking `substeps` equal steps."""
    if integrator not in INTEGRATORS:
        raise DeviceError(
            f"unknown integrator {integrator!r} (choose from {', '.join(INTEGRATORS)})"
        )
    if substeps < 1:
        raise DeviceError(f"substeps must be at least 1, not {substeps}")
    s = h / substeps
    eye = np.eye(a.shape[0])
    if integrator == "zoh":
        return expm(a * h)
    if integrator == "euler":
        one = eye + s * a
    elif integrator == "rk4":
        sa = s * a
        one = eye + sa @ (eye + sa @ (eye / 2 + sa @ (eye / 6 + sa / 24)))
    else:  # semi-implicit (symplectic) Euler: velocity first, then position with the new velocity
        one = eye + s * a
        one[0] = eye[0] + s * one[1]
    return np.linalg.matrix_power(one, substeps)


def viscous_loss(a: np.ndarray, h: float, damping: float) -> np.ndarray:
    """W with damping * z^T W z = the integral of damping*omega(t)^2 over one held period from z
    (the exact flow z(t) = exp(A t) z): W = integral of exp(A^T t) e1 e1^T exp(A t) dt, by Van
    Loan's block exponential (expm([[-A^T, Q], [0, A]] h) = [[., F12], [0, F22]], W = F22^T F12).
    """
    n = a.shape[0]
    q = np.zeros((n, n))
    q[1, 1] = 1.0
    block = np.zeros((2 * n, 2 * n))
    block[:n, :n], block[:n, n:], block[n:, n:] = -a.T, q, a
    f = expm(block * h)
    w = f[n:, n:].T @ f[:n, n:]
    return damping * 0.5 * (w + w.T)
