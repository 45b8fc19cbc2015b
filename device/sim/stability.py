"""Limits of stable rendering on a sampled knob, and flags for samples that break them.

Colgate & Schenkel (1997) / Colgate & Brown (1994): a virtual spring K and damper B rendered at
period T with zero-order hold and a backward-difference velocity is passive when
b_dev > K*T/2 + |B|, so the largest passive stiffness is K_pass = 2*(b_dev - |B|)/T.
"""

from __future__ import annotations

import numpy as np

from device.sim.params import KnobParams
from timeline.devices import StabilityFlag


def passive_stiffness(device_damping: float, virtual_damping, period: float):
    """K_pass = 2*(b_dev - |B|)/T (N*m/rad); works on scalars and arrays.

    An absurd virtual damping gives -inf (nothing is passive), which is the right answer.
    """
    with np.errstate(over="ignore"):
        return 2.0 * (device_damping - np.abs(virtual_damping)) / period


def stable_stiffness(device_damping: float, virtual_damping, period: float):
    """K_stab = 2*(b_dev + B)/T: above it a free knob oscillates with growing amplitude."""
    with np.errstate(over="ignore"):
        return 2.0 * (device_damping + np.asarray(virtual_damping)) / period


def stability_flags(
    time: np.ndarray,
    stiffness: np.ndarray,
    damping: np.ndarray,
    mass: np.ndarray | None,
    params: KnobParams,
) -> list[StabilityFlag]:
    """Flag samples above the passive stiffness, with negative damping, or cancelling inertia.

    The passivity rule applies to samples that render a spring (k > 0); a sample is flagged
    when k > K_pass, strictly, and its margin is k - K_pass.
    """
    flags = []
    k_pass = passive_stiffness(params.viscous, damping, params.period)
    over = (stiffness > 0) & (stiffness > k_pass)
    if over.any():
        flags.append(
            StabilityFlag(
                "passivity",
                "stiffness above the largest passive stiffness 2*(b_dev - |B|)/T",
                time[over],
                (stiffness - k_pass)[over],
                "N*m/rad",
            )
        )
    negative = damping < 0
    if negative.any():
        flags.append(
            StabilityFlag(
                "negative-damping",
                "negative virtual damping (active)",
                time[negative],
                -damping[negative],
                "N*m*s/rad",
            )
        )
    if mass is not None:
        cancel = params.inertia + mass <= 0
        if cancel.any():
            flags.append(
                StabilityFlag(
                    "mass-cancels-inertia",
                    f"virtual mass cancels the rotor inertia (J + m <= 0, J = {params.inertia:g})",
                    time[cancel],
                    -(params.inertia + mass[cancel]),
                    "kg*m^2",
                )
            )
    return flags
