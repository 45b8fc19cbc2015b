"""What a device may declare beyond its rate and limits: rotor dynamics, slew and actuator.

These declarations let the host check a design against the device's rendering limits
(timeline/limits/) without knowing which plugin the device is. Every field is optional: a check
that needs a number the device does not declare is skipped and says so.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from timeline.errors import DeviceError

ACTUATOR_TYPES = ("lra", "voice-coil")
# How a firmware estimates velocity and acceleration: low-passed differences, or an observer
# (a steady-state Kalman gain, or a tracking gain placing its poles). "" = not declared.
ESTIMATORS = ("filter", "kalman", "tracking")
OBSERVERS = ("kalman", "tracking")


def _check(owner: str, **values: float) -> None:
    for name, value in values.items():
        if not math.isfinite(float(value)) or value < 0:
            raise DeviceError(f"{owner}'s {name.replace('_', ' ')} must be >= 0, not {value}")


@dataclass(frozen=True)
class Dynamics:
    """A kinesthetic device's rotor and firmware as its servo loop sees them.

    inertia J (kg*m^2) and physical viscous damping b (N*m*s/rad) of the rotor and knob; `delay`
    whole servo periods between reading the encoder and applying the torque computed from it;
    the first-order low-pass cut-offs (Hz, 0 = none) on the backward-difference velocity and on
    the acceleration estimate (the difference of the velocity estimate); or, when
    `observer_gains` holds a gain L = (l0, l1, l2), an observer of angle, velocity and
    acceleration: each period it predicts them with acceleration held constant and corrects the
    prediction by L times the reading's miss. `estimator` names which: "filter", "kalman" or
    "tracking" (an observer, with its gains), or "" when the device does not declare it (an
    older USB device): then the damping and mass limits, which depend on it, cannot be checked.
    """

    inertia: float
    damping: float
    delay: int = 0
    velocity_cutoff: float = 0.0
    acceleration_cutoff: float = 0.0
    observer_gains: tuple[float, ...] = ()  # L of an observer that estimates instead, or ()
    estimator: str = "filter"  # "filter", "kalman", "tracking", or "" (not declared)

    def __post_init__(self) -> None:
        _check(
            "a device",
            inertia=self.inertia,
            damping=self.damping,
            delay=self.delay,
            velocity_cutoff=self.velocity_cutoff,
            acceleration_cutoff=self.acceleration_cutoff,
        )
        if len(self.observer_gains) not in (0, 3) or not all(
            math.isfinite(g) for g in self.observer_gains
        ):
            raise DeviceError(
                f"a device's observer gains are three numbers, not {self.observer_gains}"
            )
        if self.estimator not in ("", *ESTIMATORS):
            raise DeviceError(
                f"a device's estimator is one of {', '.join(ESTIMATORS)}, not {self.estimator!r}"
            )
        if bool(self.observer_gains) != (self.estimator in OBSERVERS):
            raise DeviceError(
                f"a device's {self.estimator or 'undeclared'} estimator "
                f"{'needs' if self.estimator in OBSERVERS else 'takes no'} observer gains"
            )
        if self.inertia <= 0:
            raise DeviceError(f"a device's inertia must be positive, not {self.inertia}")
        if int(self.delay) != self.delay:
            raise DeviceError(f"a device's delay is whole servo periods, not {self.delay}")

    @property
    def estimator_declared(self) -> bool:
        """Whether the damping and mass limits (which depend on the estimator) can be found."""
        return bool(self.estimator)


@dataclass(frozen=True)
class Actuator:
    """A vibrotactile actuator's frequency response and strength.

    `lra`: a resonator at `resonance` Hz with quality factor `q` (second-order band-pass, peak
    gain 1). `voice-coil`: flat between `low` and `high` Hz (second-order roll-offs outside).
    `peak_acceleration` is the g (9.81 m/s^2) it shakes a hand-held mass with at full scale in
    its band, as a datasheet states it.
    """

    type: str
    name: str = ""
    resonance: float = 0.0
    q: float = 0.0
    low: float = 0.0
    high: float = 0.0
    peak_acceleration: float = 1.0

    def __post_init__(self) -> None:
        if self.type not in ACTUATOR_TYPES:
            raise DeviceError(
                f"an actuator is one of {', '.join(ACTUATOR_TYPES)}, not {self.type!r}"
            )
        _check(
            "an actuator",
            resonance=self.resonance,
            q=self.q,
            low=self.low,
            high=self.high,
            peak_acceleration=self.peak_acceleration,
        )
        if self.type == "lra" and not (self.resonance > 0 and self.q > 0):
            raise DeviceError("an LRA needs a positive resonance and quality factor")
        if self.type == "voice-coil" and not (0 < self.low < self.high):
            raise DeviceError("a voice coil needs a band 0 < low < high")

    def gain(self, frequency):  # noqa: ANN001, ANN201 - scalar or array in, same out
        """Magnitude of the response (1 at the resonance / in the band) at frequencies in Hz."""
        import numpy as np

        f = np.abs(np.asarray(frequency, dtype=np.float64))
        if self.type == "lra":
            with np.errstate(divide="ignore", invalid="ignore"):
                x = f / self.resonance
                g = 1.0 / np.sqrt(1.0 + self.q**2 * (x - 1.0 / x) ** 2)
            return np.where(f > 0, g, 0.0)
        with np.errstate(divide="ignore"):
            low = (f / self.low) ** 2 / np.sqrt(1.0 + (f / self.low) ** 4)
            high = 1.0 / np.sqrt(1.0 + (f / self.high) ** 4)
        return np.where(f > 0, low * high, 0.0)

    def band(self) -> tuple[float, float]:
        """The -3 dB band in Hz."""
        if self.type == "lra":
            half = self.resonance / (2.0 * self.q)
            centre = math.sqrt(self.resonance**2 + half**2)
            return centre - half, centre + half
        return self.low, self.high

    def describe(self) -> str:
        lo, hi = self.band()
        what = (
            f"LRA at {self.resonance:g} Hz, Q {self.q:g}"
            if self.type == "lra"
            else f"voice coil {self.low:g}-{self.high:g} Hz"
        )
        return f"{self.name or self.type} ({what}; -3 dB band {lo:.1f}-{hi:.1f} Hz)"
