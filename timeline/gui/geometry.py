"""Where things are on the timeline: axis units <-> scene pixels, lanes, ruler steps (Qt-free)."""

from __future__ import annotations

import math
from dataclasses import dataclass

LANE_HEIGHT = 76
CLIP_MARGIN = 5
MIN_PX_PER_UNIT = 1e-3
MAX_PX_PER_UNIT = 1e7


def display_factor(axis: str) -> float:
    """Multiply axis units (s or rad) by this to get what the ruler shows (s or degrees)."""
    return 1.0 if axis == "time" else 180.0 / math.pi


def display_unit(axis: str) -> str:
    """The ruler's unit."""
    return "s" if axis == "time" else "°"


def axis_text(u: float, axis: str, spec: str = ".4g") -> str:
    """An axis value as the user reads it: "0.25 s", or "90°" in a position project."""
    value = format(u * display_factor(axis), spec)
    return f"{value} s" if axis == "time" else f"{value}°"


def gain_text(gain: float) -> str:
    """A gain as a designer reads it: "-6.0 dB (x0.5)"; zero is "-inf dB (x0)"."""
    if gain == 0:
        return "-inf dB (x0)"
    db = 20 * math.log10(abs(gain))
    sign = ", inverted" if gain < 0 else ""
    return f"{db:+.1f} dB (x{gain:.3g}{sign})"


@dataclass
class Geometry:
    """The mapping from the project axis to scene coordinates at the current zoom."""

    px_per_unit: float = 400.0
    lane_height: int = LANE_HEIGHT

    def x(self, u: float) -> float:
        return u * self.px_per_unit

    def u(self, x: float) -> float:
        return x / self.px_per_unit

    def lane_top(self, index: int) -> float:
        return index * self.lane_height

    def lane_at(self, y: float) -> int:
        return int(math.floor(y / self.lane_height))

    def zoomed(self, factor: float) -> float:
        """Change the zoom by factor (clamped); returns the new pixels per unit."""
        self.px_per_unit = min(MAX_PX_PER_UNIT, max(MIN_PX_PER_UNIT, self.px_per_unit * factor))
        return self.px_per_unit


def nice_step(px_per_display_unit: float, min_px: float = 70.0) -> float:
    """The smallest 1-2-5 step (display units) whose ticks are at least min_px apart."""
    raw = min_px / px_per_display_unit
    power = 10.0 ** math.floor(math.log10(raw))
    for m in (1.0, 2.0, 5.0, 10.0):
        if m * power >= raw:
            return m * power
    return 10.0 * power


def format_tick(value: float, step: float) -> str:
    """A tick label with just enough decimals for the step."""
    decimals = max(0, -int(math.floor(math.log10(step)))) if step < 1 else 0
    return f"{value:.{decimals}f}"
