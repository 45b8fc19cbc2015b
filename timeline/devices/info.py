"""What a device declares about itself."""

from __future__ import annotations

import math
from dataclasses import dataclass

from timeline.devices.errors import DeviceError

KINDS = ("kinesthetic", "vibrotactile")


@dataclass(frozen=True)
class DeviceInfo:
    """What a device declares about itself."""

    name: str
    kind: str  # "kinesthetic" or "vibrotactile"
    rate: float  # Hz: samples per second it renders
    max_output: float  # N*m (kinesthetic) or fraction of full scale (vibrotactile)
    resolution: float  # rad per encoder count (0 when the device has no encoder)
    firmware: str = ""

    def __post_init__(self) -> None:
        if self.kind not in KINDS:
            raise DeviceError(
                f"a device's kind must be kinesthetic or vibrotactile, not {self.kind!r}"
            )
        for name in ("rate", "max_output"):
            value = float(getattr(self, name))
            if not math.isfinite(value) or value <= 0:
                raise DeviceError(
                    f"a device's {name.replace('_', ' ')} must be positive, not {value}"
                )
        if not math.isfinite(float(self.resolution)) or self.resolution < 0:
            raise DeviceError(
                f"a device's resolution must be zero or positive, not {self.resolution}"
            )

    @property
    def period(self) -> float:
        """Seconds per sample."""
        return 1.0 / self.rate
