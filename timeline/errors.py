"""Errors a user can cause: each carries one clear sentence."""

import math


class HapticTimelineError(Exception):
    """Base class for mistakes in input, reported as one sentence without a traceback."""


class EditError(HapticTimelineError):
    """An edit was refused; the project is unchanged."""


class ProjectFileError(HapticTimelineError):
    """A project file could not be read or written."""


class RenderError(HapticTimelineError):
    """Rendering failed numerically (e.g. a non-finite sample)."""


class PluginError(HapticTimelineError):
    """A plugin (track kind, format or device) is unknown or failed to load."""


def finite(name: str, value: float) -> float:
    """`value` as a float, or an EditError naming `name` when it is NaN or infinite."""
    value = float(value)
    if not math.isfinite(value):
        raise EditError(f"{name} must be a finite number, not {value!r}")
    return value
