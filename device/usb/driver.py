"""The `usb` device plugin: a haptic knob or vibrotactile actuator on USB, through pyusb."""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from itertools import chain
from typing import Any

import numpy as np

from device.usb import protocol as p
from device.usb.errors import UsbDeviceError
from device.usb.link import Link, default_backend, find_devices
from device.usb.streamer import Chunker, Stream
from timeline.devices import (
    CoefficientBlock,
    Device,
    DeviceError,
    DeviceInfo,
    Hand,
    PositionProgram,
    Progress,
    Telemetry,
)


def _shown(x: float) -> float:
    """A float32 from the wire as the decimal it was written as (0.18, not 0.18000000715)."""
    return float(f"{x:.7g}")


class UsbKnob(Device):
    """A USB haptic device speaking docs/usb-protocol.md, found by VID:PID.

    `backend` is a pyusb backend (default: libusb from libusb-package, else pyusb's choice);
    `emulate=True` plugs in the emulated device instead, so everything works without hardware.
    `lead` and `block` are the seconds streamed ahead of the device and per transfer;
    `max_torque` (N*m) lowers the device's own limit.
    """

    def __init__(
        self,
        vid: int = p.DEFAULT_VID,
        pid: int = p.DEFAULT_PID,
        serial: str | None = None,
        backend: Any = None,
        emulate: bool = False,
        lead: float = 0.030,
        block: float = 0.010,
        timeout_ms: int = 1000,
        watchdog_ms: int = 50,
        max_torque: float | None = None,
    ) -> None:
        if emulate and backend is None:
            from device.usb.descriptors import Identity
            from device.usb.emulated import EmulatedBackend, EmulatedDevice

            backend = EmulatedBackend(EmulatedDevice(identity=Identity(vid=vid, pid=pid)))
        self.vid, self.pid, self.serial = int(vid), int(pid), serial
        self.backend = backend
        self.lead, self.block = float(lead), float(block)
        self.timeout_ms, self.watchdog_ms = int(timeout_ms), int(watchdog_ms)
        self.max_torque = max_torque
        self.link: Link | None = None

    @classmethod
    def discover(
        cls, vid: int = p.DEFAULT_VID, pid: int = p.DEFAULT_PID, backend: Any = None
    ) -> list[str]:
        """One line per attached device with this VID:PID; empty when none or without libusb."""
        try:
            found = find_devices(vid, pid, backend or default_backend())
        except UsbDeviceError:
            return []
        return [_describe(dev) for dev in found]

    def open(self) -> None:
        if self.link is None:
            backend = self.backend if self.backend is not None else default_backend()
            self.link = Link.open(self.vid, self.pid, backend, self.serial, self.timeout_ms)

    def close(self) -> None:
        if self.link is not None:
            self.link.abort()
            self.link.close()
            self.link = None

    @property
    def info(self) -> DeviceInfo:
        self.open()
        w = self.link.info
        kind = p.KINDS[w.kind]
        name = f"usb {self.vid:04x}:{self.pid:04x}"
        firmware = ".".join(str(x) for x in w.firmware)
        return DeviceInfo(
            name,
            kind,
            float(w.rate_hz),
            _shown(w.max_torque),
            _shown(w.encoder_resolution),
            firmware,
        )

    def play(
        self,
        program: Iterable[CoefficientBlock] | PositionProgram,
        hand: Hand | None = None,
        progress: Progress | None = None,
    ) -> Telemetry:
        """Stream coefficient blocks to the device and return the telemetry it reported."""
        if isinstance(program, PositionProgram):
            raise DeviceError(
                "the USB protocol streams time-mode coefficient blocks; play a position-mode "
                "project on the sim device"
            )
        self.open()
        link = self.link
        if hand is not None and hasattr(link.dev.backend, "set_hand"):
            link.dev.backend.set_hand(hand)  # only an emulated device has a hand to set
        blocks = list(program) if isinstance(program, Sequence) else program
        total = sum(map(len, blocks)) / link.info.rate_hz if isinstance(blocks, list) else None
        rest = iter(blocks)
        first = next(rest, None)
        mask = self._mask(first)
        limit = min(self.max_torque or np.inf, link.info.max_torque)
        stream = Stream(link, mask, limit, self.lead, self.block)
        chunker = Chunker(chain([first] if first else [], rest), p.channel_names(mask))
        try:
            link.set_limits(float(stream.limits[0]), self.watchdog_ms)
            stream.run(chunker, progress, total)
            link.stop()
        except BaseException:
            link.abort()
            raise
        tel = stream.telemetry()
        if chunker.dropped:
            names = ", ".join(sorted(chunker.dropped))
            tel = _warn(tel, f"the device does not render the {names} layers; they were not sent")
        return tel

    def _mask(self, first: CoefficientBlock | None) -> int:
        """The channels to stream: d alone to a vibrotactile device, else d, k, b (and m)."""
        channels = self.link.info.channels
        if not channels & p.CH_K:
            return p.CH_D
        if first is not None and first.m is not None:
            if not channels & p.CH_M:
                raise DeviceError("this USB device cannot render a mass layer")
            return p.ALL_CHANNELS
        return p.CH_D | p.CH_K | p.CH_B


def _warn(tel: Telemetry, message: str) -> Telemetry:
    return Telemetry(
        tel.rate,
        tel.time,
        tel.angle,
        tel.velocity,
        tel.torque,
        tel.energy,
        tel.saturated,
        tel.layers,
        tel.flags,
        (*tel.warnings, message),
    )


def _describe(dev: Any) -> str:
    """A line for `haptic-timeline devices`: identity, then what GET_INFO says."""
    where = f"usb {dev.idVendor:04x}:{dev.idProduct:04x} on bus {dev.bus} address {dev.address}"
    try:
        link = Link(dev)
    except (UsbDeviceError, p.ProtocolError) as exc:
        return f"{where} (cannot open: {exc})"
    try:
        w = link.info
        product = dev.product or "haptic device"
        return (
            f"{where}: {product}, {p.KINDS[w.kind]}, {w.rate_hz} Hz, "
            f"max {_shown(w.max_torque) * (1 if w.kind else 1e3):g}"
            f"{' of full scale' if w.kind else ' mNm'}"
        )
    finally:
        link.close()
