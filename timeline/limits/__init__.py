"""Checks of a design against a device's rendering limits and the hand's perception limits.

Device-agnostic: a device is known only by what it declares
(timeline.plugins.device_protocol.DeviceInfo and its optional Dynamics, slew and Actuator). No Qt
here; the CLI's `check` and the editor's overlays read the same findings.
"""
