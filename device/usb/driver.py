"""The `usb` device plugin: a haptic knob or vibrotactile actuator on USB, through pyusb."""

from __future__ import annotations

import os
from collections.abc import Iterable, Sequence
from dataclasses import replace
from itertools import chain
from typing import Any

import numpy as np

from device.usb import protocol as p
from device.usb.errors import UsbDeviceError
from device.usb.link import Link, default_backend, find_devices
from device.usb.streamer import Chunker, Stream
from timeline.plugins.device_protocol import (
    CoefficientBlock,
    Device,
    DeviceError,
    DeviceInfo,
    Hand,
    Monitor,
    PositionProgram,
    Progress,
    Telemetry,
)

EMULATE_ENV = "HAPTIC_TIMELINE_USB_EMULATE"
REALTIME = "realtime"  # the value of EMULATE_ENV that runs the emulated firmware on the wall clock


def _shown(x: float) -> float:
    """A float32 from the wire as the decimal it was written as (0.18, not 0.18000000715)."""
    return float(f"{x:.7g}")


class UsbKnob(Device):
    """A USB haptic device speaking docs/usb-protocol.md, found by VID:PID.

    `backend` is a pyusb backend (default: libusb from libusb-package, else pyusb's choice);
    `emulate=True` (or the environment variable HAPTIC_TIMELINE_USB_EMULATE=1) plugs in the
    emulated device instead, so everything works without hardware; `realtime=True` (or
    HAPTIC_TIMELINE_USB_EMULATE=realtime) runs its firmware on the wall clock, so a late host
    underruns it as it would a real knob (otherwise it plays as fast as the host streams).
    `lead` and `block` are the seconds streamed ahead of the device and per transfer;
    `max_torque` (N*m) lowers the device's own limit.
    """

    def __init__(
        self,
        vid: int = p.DEFAULT_VID,
        pid: int = p.DEFAULT_PID,
        serial: str | None = None,
        backend: Any = None,
        emulate: bool | None = None,
        lead: float = 0.030,
        block: float = 0.010,
        timeout_ms: int = 1000,
        watchdog_ms: int = 50,
        max_torque: float | None = None,
        realtime: bool | None = None,
    ) -> None:
        if backend is None and (_emulating() if emulate is None else emulate):
            realtime = os.environ.get(EMULATE_ENV, "") == REALTIME if realtime is None else realtime
            backend = _emulated_backend(vid, pid, realtime)
        self.vid, self.pid, self.serial = int(vid), int(pid), serial
        self.backend = backend
        self.lead, self.block = float(lead), float(block)
        self.timeout_ms, self.watchdog_ms = int(timeout_ms), int(watchdog_ms)
        self.max_torque = max_torque
        self.link: Link | None = None
        self._info: DeviceInfo | None = None

    @classmethod
    def discover(
        cls, vid: int = p.DEFAULT_VID, pid: int = p.DEFAULT_PID, backend: Any = None
    ) -> list[str]:
        """One line per attached device with this VID:PID; empty when none or without libusb."""
        if backend is None:
            backend = _emulated_backend(vid, pid) if _emulating() else default_backend()
        try:
            found = find_devices(vid, pid, backend)
        except UsbDeviceError:
            return []
        return [_describe(dev) for dev in found]

    def open(self) -> None:
        if self.link is None:
            backend = self.backend if self.backend is not None else default_backend()
            self.link = Link.open(self.vid, self.pid, backend, self.serial, self.timeout_ms)

    def warm_up(self) -> None:
        """An emulated device loads its compiled servo loop; hardware needs nothing."""
        if hasattr(self.backend, "warm_up"):
            self.backend.warm_up()

    def close(self) -> None:
        if self.link is not None:
            self.link.abort()
            self.link.close()
            self.link = None

    @property
    def info(self) -> DeviceInfo:
        """What the device declared when it was opened (opening it if it never was)."""
        if self._info is None:
            self.open()
            w = self.link.info
            self._info = DeviceInfo(
                f"usb {self.vid:04x}:{self.pid:04x}",
                p.KINDS[w.kind],
                float(w.rate_hz),
                _shown(w.max_torque),
                _shown(w.encoder_resolution),
                ".".join(str(x) for x in w.firmware),
                w.dynamics(),
            )
        return self._info

    def play(
        self,
        program: Iterable[CoefficientBlock] | PositionProgram,
        hand: Hand | None = None,
        progress: Progress | None = None,
        monitor: Monitor | None = None,
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
        chunker = Chunker(chain([] if first is None else [first], rest), p.channel_names(mask))
        try:
            link.set_limits(float(stream.limits[0]), self.watchdog_ms)
            stream.run(chunker, progress, total, monitor)
            link.stop()
        except BaseException:
            link.abort()
            raise
        tel = stream.telemetry()
        if getattr(link.dev.backend, "realtime", True):  # an emulated device may not be
            tel = replace(tel, lateness=stream.lateness.counts())
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


def _emulating() -> bool:
    return os.environ.get(EMULATE_ENV, "") not in ("", "0")


def _emulated_backend(vid: int, pid: int, realtime: bool = False) -> Any:
    from device.usb.descriptors import Identity
    from device.usb.emulated import EmulatedBackend, EmulatedDevice

    return EmulatedBackend(EmulatedDevice(identity=Identity(vid=vid, pid=pid), realtime=realtime))


def _warn(tel: Telemetry, message: str) -> Telemetry:
    return replace(tel, warnings=(*tel.warnings, message))


def _describe(dev: Any) -> str:
    """A line for `haptic-timeline devices`: identity, then what GET_INFO says."""
    where = f"usb {dev.idVendor:04x}:{dev.idProduct:04x} on bus {dev.bus} address {dev.address}"
    try:
        link = Link(dev)
    except UsbDeviceError as exc:
        return f"{where} (cannot open: {exc})"
    try:
        w = link.info
        product = dev.product or "haptic device"
        line = (
            f"{where}: {product}, {p.KINDS[w.kind]}, {w.rate_hz} Hz, "
            f"max {_shown(w.max_torque) * (1 if w.kind else 1e3):g}"
            f"{' of full scale' if w.kind else ' mNm'}"
        )
        if w.kind == p.KIND_KINESTHETIC:
            estimator = p.ESTIMATORS[w.estimator] or "estimator not declared"
            line += f", {w.delay}-period delay, {estimator}"
        return line
    finally:
        link.close()
