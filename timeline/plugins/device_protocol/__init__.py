"""The host-side device protocol: what a device declares, what it plays, what it reports.

A device plays coefficient blocks of the torque law

    tau = d - k*theta - b*theta_dot - m*theta_ddot

(time mode) or a position program of tables over angle (position mode), and returns telemetry.
Plugins are found by name through the `haptic_timeline.devices` entry point group; this module
never imports a particular plugin.
"""

from importlib import import_module
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:  # what pyright and IDEs see; at run time each name loads on first use
    from timeline.plugins.device_protocol.device import Device, Progress, device_names, open_device
    from timeline.plugins.device_protocol.dynamics import (
        ACTUATOR_TYPES,
        ESTIMATORS,
        Actuator,
        Dynamics,
    )
    from timeline.plugins.device_protocol.hand import (
        DEFAULT_PUSH_MNM,
        DEFAULT_TURN_DEG_PER_S,
        HAND_MODES,
        Hand,
    )
    from timeline.plugins.device_protocol.hand_models import HAND_MODELS, HandModel
    from timeline.plugins.device_protocol.info import KINDS, DeviceInfo
    from timeline.plugins.device_protocol.lateness import Lateness, LatenessMeter
    from timeline.plugins.device_protocol.program import (
        CoefficientBlock,
        PositionProgram,
        PositionTable,
        Program,
    )
    from timeline.plugins.device_protocol.telemetry import (
        TELEMETRY_COLUMNS,
        LiveTelemetry,
        Monitor,
        StabilityFlag,
        Telemetry,
        merge_flags,
    )

from timeline.errors import DeviceError, HandSpecError  # what a device plugin raises

# Public names -> the submodule defining them, loaded on first use: the light ones (dynamics,
# hand, info) do not pull in numpy with the telemetry and programs.
_EXPORTS = {
    **dict.fromkeys(("Device", "Progress", "device_names", "open_device"), "device"),
    **dict.fromkeys(("ACTUATOR_TYPES", "ESTIMATORS", "Actuator", "Dynamics"), "dynamics"),
    **dict.fromkeys(("DEFAULT_PUSH_MNM", "DEFAULT_TURN_DEG_PER_S", "HAND_MODES", "Hand"), "hand"),
    **dict.fromkeys(("HAND_MODELS", "HandModel"), "hand_models"),
    **dict.fromkeys(("KINDS", "DeviceInfo"), "info"),
    **dict.fromkeys(("Lateness", "LatenessMeter"), "lateness"),
    **dict.fromkeys(("CoefficientBlock", "PositionProgram", "PositionTable", "Program"), "program"),
    **dict.fromkeys(
        (
            "TELEMETRY_COLUMNS",
            "LiveTelemetry",
            "Monitor",
            "StabilityFlag",
            "Telemetry",
            "merge_flags",
        ),
        "telemetry",
    ),  # fmt: skip
}


def __getattr__(name: str) -> Any:
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f"module 'timeline.plugins.device_protocol' has no attribute {name!r}")
    value = getattr(import_module(f"timeline.plugins.device_protocol.{module}"), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    """The public names, loaded or not (what an IDE or a notebook completes)."""
    return sorted(__all__)


__all__ = [
    "ACTUATOR_TYPES",
    "DEFAULT_PUSH_MNM",
    "DEFAULT_TURN_DEG_PER_S",
    "HAND_MODELS",
    "HAND_MODES",
    "KINDS",
    "TELEMETRY_COLUMNS",
    "ESTIMATORS",
    "Actuator",
    "CoefficientBlock",
    "Device",
    "DeviceError",
    "DeviceInfo",
    "Dynamics",
    "Hand",
    "HandModel",
    "HandSpecError",
    "Lateness",
    "LatenessMeter",
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
