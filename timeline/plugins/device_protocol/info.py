"""What a device declares about itself."""

from __future__ import annotations

import math
from dataclasses import dataclass

from timeline.errors import DeviceError
from timeline.plugins.device_protocol.dynamics import Actuator, Dynamics
from timeline.plugins.device_protocol.lateness import LEAD_SECONDS

KINDS = ("kinesthetic", "vibrotactile")


@dataclass(frozen=True)
class DeviceInfo:
    """What a device declares about itself.

    The optional declarations feed the design checks (timeline/limits/): `dynamics` (rotor and
    servo loop, kinesthetic devices), `slew` (largest output change per second, in max_output
    units per second) and `actuator` (a vibrotactile device's frequency response). `lead` is how
    far ahead of its playing (s) a live stream hands the device its blocks: what it keeps queued.
    """

    name: str
    kind: str  # "kinesthetic" or "vibrotactile"
    rate: float  # Hz: samples per second it renders
    max_output: float  # N*m (kinesthetic) or fraction of full scale (vibrotactile)
    resolution: float  # rad per encoder count (0 when the device has no encoder)
    firmware: str = ""
    dynamics: Dynamics | None = None
    slew: float | None = None
    actuator: Actuator | None = None
    lead: float = LEAD_SECONDS

    def __post_init__(self) -> None:
        if self.kind not in KINDS:
            raise DeviceError(
                f"a device's kind must be kinesthetic or vibrotactile, not {self.kind!r}"
            )
        for name in ("rate", "max_output", "lead"):
            value = float(getattr(self, name))
            if not math.isfinite(value) or value <= 0:
                raise DeviceError(
                    f"a device's {name.replace('_', ' ')} must be positive, not {value}"
                )
        if not math.isfinite(float(self.resolution)) or self.resolution < 0:
            raise DeviceError(
                f"a device's resolution must be zero or positive, not {self.resolution}"
            )
        if self.slew is not None and not (math.isfinite(float(self.slew)) and self.slew > 0):
            raise DeviceError(f"a device's slew limit must be positive, not {self.slew}")

    @property
    def period(self) -> float:
        """Seconds per sample."""
        return 1.0 / self.rate
