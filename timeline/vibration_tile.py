"""A tile holding a vibration design: envelopes and emphasis as data, carrier made on render."""

from __future__ import annotations

import json
from dataclasses import dataclass

import numpy as np

from timeline.errors import EditError
from timeline.quality import QualityPreset
from timeline.vibration_design import VibrationDesign

SHARPNESS_CONVENTIONS = ("sqrt", "linear")


@dataclass(frozen=True)
class VibrationTile:
    """A vibrotactile design as a tile: its carrier is synthesised exactly at any rate.

    `sharpness` names the AHAP sharpness convention of the file it came from ("sqrt": Meta's
    sharpness = sqrt(frequency), "linear": sharpness = frequency), so an export writes it back.
    """

    design: VibrationDesign
    name: str = "vibration"
    source: str = ""
    sharpness: str = "sqrt"

    reverse_shift = 0.0

    def __post_init__(self) -> None:
        if not isinstance(self.design, VibrationDesign):
            raise EditError("a vibration tile holds a VibrationDesign")
        if self.sharpness not in SHARPNESS_CONVENTIONS:
            raise EditError(
                f"unknown sharpness convention {self.sharpness!r} (choose sqrt or linear)"
            )

    @property
    def duration(self) -> float:
        return self.design.extent

    @property
    def key(self) -> str:
        d = self.design
        return "vibration:" + json.dumps(
            [
                d.amplitude,
                d.frequency,
                [(e.time, e.amplitude, e.frequency) for e in d.emphasis],
                d.duration,
            ]
        )

    def evaluate(self, u: np.ndarray) -> np.ndarray:
        """Exact drive values (fraction of full scale) at times u; zero outside the tile."""
        return self.design.render(u)

    def render(self, u0: float, du: float, n: int, quality: QualityPreset) -> np.ndarray:
        # The carrier is never decimated: interpolating it would change its frequency content.
        return self.design.render(u0 + du * np.arange(n))

    def with_name(self, name: str) -> VibrationTile:
        return VibrationTile(self.design, name, self.source, self.sharpness)
