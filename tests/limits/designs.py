"""Designs built to sit at, just below and just above each limit."""

from __future__ import annotations

from timeline import edits, generator
from timeline.model import Project
from timeline.plugins.device_protocol import DeviceInfo, Dynamics

KNOB = DeviceInfo(
    "test knob", "kinesthetic", 10_000.0, 0.18, 0.0, "", Dynamics(1e-5, 1e-4, 0, 2000.0, 200.0)
)


def layered(kind: str, value: float, seconds: float = 0.2, at: float = 0.0) -> Project:
    """A time project with one constant clip of `value` (SI) on a track of `kind`."""
    p = edits.new_project("time")
    p, track = edits.add_track(p, kind, kind)
    p = edits.set_track(p, track, full_scale=abs(value) or 1.0)
    p, tile = edits.add_tile(p, generator("constant", seconds, "level", value=1.0))
    p, _ = edits.add_clip(p, track, tile, at, gain=1.0 if value >= 0 else -1.0)
    return p


def tone(frequency: float, amplitude: float, seconds: float = 0.3) -> Project:
    """A time project with a sine of `amplitude` (SI drive) at `frequency` Hz."""
    p = edits.new_project("time")
    p, track = edits.add_track(p, "drive", "drive")
    p = edits.set_track(p, track, full_scale=amplitude)
    p, tile = edits.add_tile(p, generator("sine", seconds, "tone", frequency=frequency))
    p, _ = edits.add_clip(p, track, tile, 0.0)
    return p
