"""Markers (named places on the axis) and the loop region: part of a project's state.

Positions are in axis units (seconds, or radians in a position project). The edits that change
them are in timeline.edits.markers.
"""

from __future__ import annotations

from dataclasses import dataclass

from timeline.errors import EditError, finite


@dataclass(frozen=True)
class Marker:
    """A named place on the axis (a cue in time, a setting such as "Lo" on a knob)."""

    name: str
    at: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "at", finite("a marker's position", self.at))
        if not self.name.strip():
            raise EditError("a marker needs a name")


@dataclass(frozen=True)
class LoopRegion:
    """The range playback loops over, [start, stop)."""

    start: float
    stop: float

    def __post_init__(self) -> None:
        start = finite("the loop's start", self.start)
        stop = finite("the loop's end", self.stop)
        if stop <= start:
            raise EditError("a loop region must end after it starts")
        object.__setattr__(self, "start", start)
        object.__setattr__(self, "stop", stop)
