"""A tile holding a vibration design: envelopes and emphasis as data, carrier made on render."""

from __future__ import annotations

import json
from dataclasses import dataclass
from typing import Any

import numpy as np

from timeline.errors import EditError
from timeline.signal.render_presets import QualityPreset
from timeline.signal.vibration_design import Emphasis, VibrationDesign

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
                np.asarray(d.amplitude).tolist(),
                np.asarray(d.frequency).tolist(),
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

    def as_json(self) -> dict[str, Any]:
        """The tile as JSON-ready data (the .htl and .otio layout, docs/file-format.md)."""
        d = self.design
        return {
            "type": "vibration",
            "name": self.name,
            "source": self.source,
            "sharpness": self.sharpness,
            "duration": d.duration,
            "amplitude": np.asarray(d.amplitude).tolist(),
            "frequency": np.asarray(d.frequency).tolist(),
            "emphasis": [[e.time, e.amplitude, e.frequency] for e in d.emphasis],
        }

    @classmethod
    def from_json(cls, data: Any) -> VibrationTile:
        """The tile as_json wrote, or an EditError saying what is malformed."""
        if not isinstance(data, dict):
            raise EditError("a vibration tile must be an object")

        def rows(key: str, width: int) -> list[tuple[float, ...]]:
            value = data.get(key)
            if not isinstance(value, list) or not all(
                isinstance(r, list)
                and len(r) == width
                and all(isinstance(x, int | float) and not isinstance(x, bool) for x in r)
                for r in value
            ):
                raise EditError(f"a vibration tile's {key} should be lists of {width} numbers")
            return [tuple(float(x) for x in r) for r in value]

        duration, name = data.get("duration"), data.get("name")
        if isinstance(duration, bool) or not isinstance(duration, int | float):
            raise EditError("a vibration tile's duration should be a number")
        if not isinstance(name, str) or not isinstance(data.get("sharpness"), str):
            raise EditError("a vibration tile needs a name and a sharpness convention")
        try:
            design = VibrationDesign(
                tuple(rows("amplitude", 2)),  # type: ignore[arg-type]
                tuple(rows("frequency", 2)),  # type: ignore[arg-type]
                tuple(Emphasis(*e) for e in rows("emphasis", 3)),
                float(duration),
            )
        except OverflowError:  # an integer beyond float range, e.g. 10**400
            raise EditError("a vibration tile holds a number too large to use") from None
        return cls(design, name, str(data.get("source", "")), data["sharpness"])

    def with_name(self, name: str) -> VibrationTile:
        return VibrationTile(self.design, name, self.source, self.sharpness)
