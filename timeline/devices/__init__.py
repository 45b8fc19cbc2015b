"""The host-side device protocol: what a device declares, what it plays, what it reports.

A device plays coefficient blocks of the torque law

    tau = d - k*theta - b*theta_dot - m*theta_ddot

(time mode) or a position program of tables over angle (position mode), and returns telemetry.
Plugins are found by name through the `haptic_timeline.devices` entry point group; this module
never imports a particular plugin.
"""

from timeline.devices.device import Device, Progress, device_names, open_device
from timeline.devices.dynamics import ACTUATOR_TYPES, Actuator, Dynamics
from timeline.devices.errors import DeviceError, HandSpecError
from timeline.devices.hand import DEFAULT_PUSH_MNM, DEFAULT_TURN_DEG_PER_S, HAND_MODES, Hand
from timeline.devices.info import KINDS, DeviceInfo
from timeline.devices.program import CoefficientBlock, PositionProgram, PositionTable, Program
from timeline.devices.telemetry import (
    TELEMETRY_COLUMNS,
    LiveTelemetry,
    Monitor,
    StabilityFlag,
    Telemetry,
    merge_flags,
)

__all__ = [
    "ACTUATOR_TYPES",
    "DEFAULT_PUSH_MNM",
    "DEFAULT_TURN_DEG_PER_S",
    "HAND_MODES",
    "KINDS",
    "TELEMETRY_COLUMNS",
    "Actuator",
    "CoefficientBlock",
    "Device",
    "DeviceError",
    "DeviceInfo",
    "Dynamics",
    "Hand",
    "HandSpecError",
    "LiveTelemetry",
    "Monitor",
    "PositionProgram",
    "PositionTable",
    "Program",
    "Progress",
    "StabilityFlag",
    "Telemetry",
    "device_names",
    "merge_flags",
    "open_device",
]
