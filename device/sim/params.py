"""The simulated knob's physical and firmware constants (defaults: the paper's knob)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from numbers import Real

import numpy as np

from device.sim.observer import NOISE, kalman_gains, tracking_gains
from timeline.plugins.device_protocol import ESTIMATORS, DeviceError, Dynamics

ENCODER_QUANTUM = math.radians(0.001)  # rad per count: 0.001 deg


@dataclass(frozen=True)
class KnobParams:
    """A knob: rotor, friction, encoder, amplifier limit, estimator filters and watchdog.

    Defaults follow the paper's knob (10 kHz, 0.001 deg encoder, 180 mNm max continuous
    torque); the rotor inertia and friction are stated in docs/devices.md.
    """

    rate: float = 10_000.0  # Hz servo rate
    quantum: float = ENCODER_QUANTUM  # rad per encoder count; 0 = ideal sensor
    max_torque: float = 0.18  # N*m max continuous torque
    inertia: float = 1e-5  # kg*m^2 rotor and knob (J)
    viscous: float = 1e-4  # N*m*s/rad physical viscous damping (b_dev)
    coulomb: float = 1e-3  # N*m Coulomb friction
    velocity_cutoff: float = 2_000.0  # Hz first-order low-pass on the velocity estimate; 0 = none
    acceleration_cutoff: float = 200.0  # Hz low-pass on the acceleration estimate; 0 = none
    estimator: str = "kalman"  # "kalman", "filter" (differences, low-passed) or "tracking"
    observer_noise: float = NOISE  # the Kalman observer's noise, fraction of a 3-point estimate's
    observer_bandwidth: float = 1000.0  # Hz: where the tracking observer's three poles sit
    gains: tuple[float, ...] = ()  # an observer's L as a firmware holds it; () = from the above
    # (a device option takes "l0,l1,l2")
    slew: float = 0.0  # N*m/s the amplifier's output may change by at most; 0 = no limit
    delay: int = 0  # servo periods between reading the encoder and applying its torque (0 or 1)
    watchdog_timeout: float = 0.005  # s without a block before the torque starts ramping down
    watchdog_ramp: float = 0.010  # s from the last torque to zero
    firmware: str = "sim-1.0"

    def __post_init__(self) -> None:
        for name in self.__dataclass_fields__:
            value = getattr(self, name)
            if name in ("firmware", "estimator", "gains"):
                continue
            if not isinstance(value, Real):
                raise DeviceError(
                    f"the knob's {name.replace('_', ' ')} ({name}) is a number, not {value!r}"
                )
            if not math.isfinite(value) or value < 0:
                raise DeviceError(f"the knob's {name.replace('_', ' ')} must be >= 0, not {value}")
        if self.estimator not in ESTIMATORS:
            raise DeviceError(
                f"the knob's estimator is {', '.join(ESTIMATORS)}, not {self.estimator!r}"
            )
        if not 0.0 < self.observer_noise < 1.0:
            raise DeviceError(
                "the knob's observer noise is a fraction between 0 and 1, "
                f"not {self.observer_noise}"
            )
        if self.gains:
            object.__setattr__(self, "gains", _gains(self.gains, self.estimator))
        if self.delay not in (0, 1):
            raise DeviceError(f"the knob's delay is 0 or 1 servo period, not {self.delay}")
        if self.rate <= 0 or self.inertia <= 0:  # a max torque of 0 plays no torque
            raise DeviceError("the knob's rate and inertia must be positive")

    @classmethod
    def option_names(cls) -> tuple[str, ...]:
        """The parameters a device option may set (every field)."""
        return tuple(cls.__dataclass_fields__)

    @cached_property
    def dynamics(self) -> Dynamics:
        """The rotor and servo loop as the design checks see them (made once: flags use it per
        block)."""
        gains = self.observer_gains
        return Dynamics(
            self.inertia,
            self.viscous,
            int(self.delay),
            self.velocity_cutoff,
            self.acceleration_cutoff,
            () if gains is None else tuple(float(g) for g in gains),
            self.estimator,
        )

    @cached_property
    def observer_gains(self) -> np.ndarray | None:
        """The observer's gain L (observer.py, or `gains` when given), or None when the filters
        estimate."""
        if self.estimator == "filter":
            return None
        if self.gains:
            return np.array(self.gains, dtype=np.float64)
        if self.estimator == "kalman":
            return kalman_gains(self.period, self.observer_noise)
        if self.estimator == "tracking":
            return tracking_gains(self.period, self.observer_bandwidth)
        return None

    @property
    def period(self) -> float:
        return 1.0 / self.rate

    def smoothing(self, cutoff: float) -> float:
        """Gain of a first-order low-pass at a cut-off (1.0 = no filtering)."""
        return 1.0 if cutoff <= 0 else 1.0 - math.exp(-2.0 * math.pi * cutoff / self.rate)


def _gains(value: object, estimator: str) -> tuple[float, float, float]:
    """An observer's L from three numbers or "l0,l1,l2" (a device option), or DeviceError."""
    parts = value.split(",") if isinstance(value, str) else value
    try:
        gains = tuple(float(g) for g in parts)  # type: ignore[union-attr]
    except (TypeError, ValueError):
        gains = ()
    if estimator == "filter" or len(gains) != 3 or not all(math.isfinite(g) for g in gains):
        raise DeviceError(
            f"the knob's observer gains are three finite numbers l0,l1,l2 for a kalman or "
            f"tracking estimator, not {value!r} for {estimator}"
        )
    return gains
