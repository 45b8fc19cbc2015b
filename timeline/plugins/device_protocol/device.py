"""The device plugin interface, and finding a plugin by name."""

from __future__ import annotations

import abc
import inspect
from collections.abc import Callable
from types import TracebackType
from typing import Any

from timeline import plugins
from timeline.errors import DeviceError
from timeline.plugins.device_protocol.hand import Hand
from timeline.plugins.device_protocol.info import DeviceInfo
from timeline.plugins.device_protocol.program import Program
from timeline.plugins.device_protocol.telemetry import Monitor, Telemetry

Progress = Callable[[float, float | None], None]  # (seconds played, total seconds or None)


class Device(abc.ABC):
    """A device plugin: declares itself, opens, plays a program, reports telemetry."""

    @property
    @abc.abstractmethod
    def info(self) -> DeviceInfo:
        """What the device declares (rate, kind, limits)."""

    def open(self) -> None:  # noqa: B027 - devices without a connection need nothing here
        """Connect to the device (idempotent)."""

    def close(self) -> None:  # noqa: B027
        """Release the device (idempotent); the output ends at zero."""

    def warm_up(self) -> None:  # noqa: B027 - a device with nothing to load needs nothing here
        """Load what a first play needs (compiled loops) without playing anything, so Play
        starts at once; the editor calls it on a background thread once its window is up."""

    def __enter__(self) -> Device:
        self.open()
        return self

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        self.close()

    @abc.abstractmethod
    def play(
        self,
        program: Program,
        hand: Hand | None = None,
        progress: Progress | None = None,
        monitor: Monitor | None = None,
    ) -> Telemetry:
        """Play coefficient blocks (or a position program) and return what happened.

        `monitor`, if given, receives each piece of telemetry as the device reports it; a
        monitored play is watched live by a host that judges the design itself (the editor's
        findings), so a device may leave the judgement of the whole play (`Telemetry.flags`
        of stability) out of it, as the sim and the USB knob's stream process do.
        """

    @classmethod
    def discover(cls) -> list[str]:
        """Describe each unit of this device type that is present (empty when none)."""
        return []

    @classmethod
    def missing(cls) -> str | None:
        """Why no unit can be found on this computer (a library the plugin needs is missing),
        in one sentence; None when nothing is missing."""
        return None

    @classmethod
    def options(cls) -> tuple[str, ...] | None:
        """The options the constructor takes (`--device-option KEY=VALUE`); None when it takes
        any keyword."""
        params = list(inspect.signature(cls.__init__).parameters.values())[1:]
        if any(p.kind is p.VAR_KEYWORD for p in params):
            return None
        return tuple(p.name for p in params if p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY))


def device_names() -> list[str]:
    """Names of the registered device plugins."""
    return sorted(plugins.load_group(plugins.DEVICES))


def open_device(name: str = "sim", **options: Any) -> Device:
    """Find a device plugin by name, construct it with options, open it and return it.

    An option the plugin does not take is refused with one sentence naming the ones it takes.
    """
    cls = plugins.get(plugins.DEVICES, name)
    known = cls.options()
    unknown = [key for key in options if known is not None and key not in known]
    if unknown:
        raise DeviceError(
            f"the {name} device does not take those options ({', '.join(unknown)}); it takes "
            f"{', '.join(known or ()) or 'none'}"
        )
    try:
        device = cls(**options)
    except TypeError as exc:
        if not options:
            raise
        raise DeviceError(f"the {name} device does not take those options ({exc})") from None
    device.open()
    return device
