"""Flags for samples the simulated knob cannot render stably: stiffness, damping and mass.

The limits come from the device-agnostic servo-loop model (timeline/limits/servo.py) with the
knob's own inertia, damping, estimator filters and delay:

* stiffness: passivity, K_pass = (b_dev - |B|) / (T*(1/2 + D)) (Colgate & Schenkel 1997, with
  a delay of D periods);
* damping: B above the largest damping the free knob renders stably (about 2*J/T), or negative
  (active);
* mass: m outside the band the loop renders stably, or J + m <= 0 (the inertia cancelled).
"""

from __future__ import annotations

import numpy as np

from timeline.limits import servo
from timeline.plugins.device_protocol import Dynamics, StabilityFlag


def passive_stiffness(device_damping: float, virtual_damping, period: float, delay: int = 0):
    """K_pass = (b_dev - |B|)/(T*(1/2 + D)) (N*m/rad); works on scalars and arrays."""
    return servo.passive_stiffness(device_damping, virtual_damping, period, delay)


def stable_stiffness(device_damping: float, virtual_damping, period: float, delay: int = 0):
    """K_stab = (b_dev + B)/(T*(1/2 + D)): above it a free knob oscillates with growing
    amplitude (2*(b_dev + B)/T without delay; the loop model's edge within 0.1 % at 10 kHz)."""
    with np.errstate(over="ignore"):
        return (device_damping + np.asarray(virtual_damping)) / (period * (0.5 + delay))


def stability_flags(
    time: np.ndarray,
    stiffness: np.ndarray,
    damping: np.ndarray,
    mass: np.ndarray | None,
    dyn: Dynamics,
    period: float,
    loads: tuple[servo.Load, ...] = (servo.FREE,),
) -> list[StabilityFlag]:
    """Flag samples beyond the stiffness, damping or mass limits of the knob's servo loop.

    `dyn` and `period` are the knob's (KnobParams.dynamics and .period, or what a USB device
    declares); `loads` the hands the whole loop is judged with (the sim: the hand it plays).
    Without a declared estimator only passivity and negative damping are flagged: the damping
    and mass limits and the whole loop depend on it.

    Each rule flags samples strictly beyond its limit; a flag's margins say by how much. A rule
    is first tested on the layers' extremes (a few reductions per block, where per-sample
    masks cost more than the servo loop) and per sample only when an extreme is beyond it.
    """
    flags: list[StabilityFlag] = []
    if not time.size:
        return flags

    def flag(kind: str, message: str, where: np.ndarray, margin: np.ndarray, unit: str) -> None:
        if where.any():
            flags.append(StabilityFlag(kind, message, time[where], margin[where], unit))

    lowest_pass = passive_stiffness(dyn.damping, np.abs(damping).max(), period, dyn.delay)
    spring = np.maximum(stiffness, 0.0)  # with |B| > b_dev even k = 0 is not passive
    if spring.max() > lowest_pass:  # K_pass falls as |B| grows: none is lower
        k_pass = passive_stiffness(dyn.damping, damping, period, dyn.delay)
        flag(
            "passivity",
            "stiffness above the largest passive stiffness (b_dev - |B|)/(T*(1/2 + delay)); "
            "with |B| > b_dev no stiffness is passive, not even 0",
            spring > k_pass,
            spring - k_pass,
            "N*m/rad",
        )
    if damping.min() < 0:
        flag("negative-damping", "negative virtual damping (active)", damping < 0, -damping,
             "N*m*s/rad")  # fmt: skip
    declared = dyn.estimator_declared  # the damping and mass limits depend on the estimator
    b_max = servo.damping_limit(dyn, period) if declared else np.inf
    if damping.max() > b_max:
        flag(
            "damping-limit",
            f"virtual damping above the largest the servo loop renders stably "
            f"({b_max:.4g} N*m*s/rad)",
            damping > b_max,
            damping - b_max,
            "N*m*s/rad",
        )
    if declared:
        _whole_loop(flags, time, stiffness, damping, mass, dyn, period, loads)
    if mass is None:
        return flags
    low, high = servo.mass_limits(dyn, period) if declared else (-dyn.inertia, np.inf)
    m_low, m_high = mass.min(), mass.max()
    if dyn.inertia + m_low <= 0 or m_high > high or m_low < low:
        cancel = dyn.inertia + mass <= 0
        flag(
            "mass-cancels-inertia",
            f"virtual mass cancels the rotor inertia (J + m <= 0, J = {dyn.inertia:g})",
            cancel,
            -(dyn.inertia + mass),
            "kg*m^2",
        )
        flag(
            "mass-limit",
            f"virtual mass outside the band the servo loop renders stably ({low:.4g} to "
            f"{high:.4g} kg*m^2)",
            ~cancel & ((mass > high) | (mass < low)),
            np.where(mass > high, mass - high, low - mass),
            "kg*m^2",
        )
    return flags


def _whole_loop(
    flags: list[StabilityFlag],
    time: np.ndarray,
    stiffness: np.ndarray,
    damping: np.ndarray,
    mass: np.ndarray | None,
    dyn: Dynamics,
    period: float,
    loads: tuple[servo.Load, ...],
) -> None:
    """Append `unstable-loop` at samples where every layer is inside its own limit and the loop
    with all of them (and the loads) is unstable; margin: growth per period minus 1."""
    loop = servo.whole_loop(dyn, period, stiffness, damping, mass, loads)
    if not loop.unstable:  # stable with every load: no sample to explain
        return
    bad = loop.any & servo.layers_inside(dyn, period, stiffness, damping, mass)
    if bad.any():
        hands = ", ".join(name for name, where in loop.unstable.items() if (where & bad).any())
        flags.append(
            StabilityFlag(
                "unstable-loop",
                "stiffness, damping and mass each inside their own limit but the servo loop "
                f"with all of them is unstable ({hands})",
                time[bad],
                loop.radius[bad] - 1.0,
                "growth per period - 1",
            )
        )
