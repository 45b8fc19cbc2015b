"""The `audio` device plugin: vibrotactile output of the drive layer to a sound card."""

from device.audio.actuator import AudioActuator

__all__ = ["AudioActuator"]
