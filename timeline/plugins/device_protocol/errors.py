"""Errors of devices and hand specifications."""

from __future__ import annotations

from timeline.errors import HapticTimelineError


class DeviceError(HapticTimelineError):
    """A device is missing, refused a request or failed while playing."""


class HandSpecError(HapticTimelineError):
    """A --hand specification could not be understood."""
