"""Times in an exported OTIO timeline: exact at the project's rate, or whole frames of a video rate.

OTIO's editorial adapters (FCP 7 XML, FCP X XML, CMX 3600) write SMPTE timecode, which exists
only at video rates (OTIO's own list: 23.976, 24, 25, 29.97, 30, 48, 50, 59.94, 60 and a few
more); a project's 10 kHz is not one of them. Asked for a video rate, every clip boundary is
rounded to its nearest frame from its exact time, so no rounding accumulates along a track.
"""

from __future__ import annotations

import math

import opentimelineio as otio

from timeline.errors import FormatError


def video_rate(asked: float) -> float:
    """OTIO's exact timecode rate for a rate as a person writes it (23.976 -> 24000/1001)."""
    if not math.isfinite(asked) or asked <= 0:
        raise FormatError(f"an OTIO frame rate must be a positive number, not {asked!r}")
    nearest = otio.opentime.RationalTime.nearest_valid_timecode_rate(asked)
    if abs(nearest - asked) > 0.01:
        raise FormatError(
            f"{asked:g} is not a timecode rate OTIO's editorial adapters accept; give a video "
            "rate such as 23.976, 24, 25, 29.97 or 30"
        )
    return nearest


class Clock:
    """Seconds as OTIO times: exact at `rate`, or rounded to whole frames when `frames`."""

    def __init__(self, rate: float, frames: bool) -> None:
        self.rate = rate
        self.frames = frames

    def count(self, seconds: float) -> float:
        """The time in units of the rate (a whole number of frames when rounding)."""
        value = seconds * self.rate
        return float(round(value)) if self.frames else value

    def at(self, seconds: float) -> otio.opentime.RationalTime:
        return otio.opentime.RationalTime(self.count(seconds), self.rate)

    def span(self, start: float, end: float) -> otio.opentime.RationalTime:
        """The duration from start to end, each rounded on its own when counting frames."""
        return otio.opentime.RationalTime(self.count(end) - self.count(start), self.rate)

    def whole(self, seconds: float) -> otio.opentime.RationalTime:
        """A duration covering `seconds` (rounded up to whole frames): a medium's length."""
        value = seconds * self.rate
        return otio.opentime.RationalTime(
            float(math.ceil(value - 1e-9)) if self.frames else value, self.rate
        )
