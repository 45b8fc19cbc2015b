"""The `usb` device plugin: a haptic knob or vibrotactile actuator on USB, through pyusb."""

from __future__ import annotations

import math
import os
from collections.abc import Iterable, Sequence
from dataclasses import replace
from itertools import chain
from typing import Any

import numpy as np

from device.usb import protocol as p
from device.usb.errors import UsbDeviceError
from device.usb.link import Link, default_backend, find_devices
from device.usb.process import StreamProcess
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
LEAD_S = 0.030  # the protocol's default lead (docs/usb-protocol.md, section 4)
# The lead of a stream in a process of its own: blocks are handed to it this far ahead of their
# play and it keeps the device's queue this full, so a host stalled for less (its interpreter
# lock held by the GUI, a render) and a streaming process woken late (a loaded machine) lose
# nothing; an edit is felt this much later.
PROCESS_LEAD_S = 0.100
WATCHDOG_MARGIN_MS = 20  # the default watchdog: the lead plus a report and a block (50 ms at 30)


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
    `lead` and `block` are the seconds streamed ahead of the device (default 30 ms, 100 ms
    from a process of its own) and per transfer; `watchdog_ms` is the device's watchdog (default
    the lead plus 20 ms); `max_torque` (N*m) lowers the device's own limit. `process`: stream
    from a process of its own (device.usb.process), so the host's other threads cannot delay a
    transfer; by default when the device runs on the wall clock (hardware, or `realtime`) and
    no backend object is given.
    """

    def __init__(
        self,
        vid: int = p.DEFAULT_VID,
        pid: int = p.DEFAULT_PID,
        serial: str | None = None,
        backend: Any = None,
        emulate: bool | None = None,
        lead: float | None = None,
        block: float = 0.010,
        timeout_ms: int = 1000,
        watchdog_ms: int | None = None,
        max_torque: float | None = None,
        realtime: bool | None = None,
        process: bool | None = None,
    ) -> None:
        _check_options(vid, pid, serial, lead, block, timeout_ms, watchdog_ms, max_torque)
        serial = None if serial is None else str(serial)  # digits arrive as a number
        for flag, value in (("emulate", emulate), ("realtime", realtime), ("process", process)):
            if value is not None and not isinstance(value, bool):
                raise DeviceError(f"the USB option {flag} is true or false, not {value!r}")
        emulated = backend is None and (_emulating() if emulate is None else emulate)
        if emulated:
            realtime = os.environ.get(EMULATE_ENV, "") == REALTIME if realtime is None else realtime
        # A device on the wall clock (hardware, or the emulation in real time) is streamed from
        # a process of its own unless told otherwise; a given backend object is this process's.
        if process is None:
            process = backend is None and (realtime or not emulated)
        self.opener: tuple | None = None
        if process:
            self.opener = (_open_emulated if emulated else _open_hardware,
                           (vid, pid, serial, timeout_ms, bool(realtime)))  # fmt: skip
        elif emulated:
            backend = _emulated_backend(vid, pid, bool(realtime))
        self.vid, self.pid, self.serial = int(vid), int(pid), serial
        self.backend = backend
        lead = (PROCESS_LEAD_S if process else LEAD_S) if lead is None else lead
        self.lead, self.block = float(lead), float(block)
        watchdog_ms = (
            round(self.lead * 1000) + WATCHDOG_MARGIN_MS if watchdog_ms is None else watchdog_ms
        )
        self.timeout_ms, self.watchdog_ms = int(timeout_ms), int(watchdog_ms)
        self.max_torque = max_torque
        self.link: Link | None = None
        self.remote: StreamProcess | None = None
        self.underruns = 0  # samples played from an empty queue in the last play (its last report)
        self._info: DeviceInfo | None = None

    @classmethod
    def options(cls) -> tuple[str, ...]:
        """What `--device-option` may set: every constructor argument but the backend object."""
        return tuple(name for name in super().options() or () if name != "backend")

    @classmethod
    def missing(cls) -> str | None:
        """Without libusb nothing can be found (the emulated device needs none)."""
        if _emulating() or default_backend() is not None:
            return None
        return (
            "no USB library was found: install libusb (apt-get install libusb-1.0-0) or "
            "pip install libusb-package"
        )

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
        if self.opener is not None:
            if self.remote is None:
                self.remote = StreamProcess(*self.opener)
        elif self.link is None:
            backend = self.backend if self.backend is not None else default_backend()
            self.link = Link.open(self.vid, self.pid, backend, self.serial, self.timeout_ms)

    def warm_up(self) -> None:
        """An emulated device loads its compiled servo loop (in its process, when it has one,
        as it opens); hardware needs nothing."""
        if hasattr(self.backend, "warm_up"):
            self.backend.warm_up()

    def close(self) -> None:
        if self.remote is not None:
            self.remote.close()
            self.remote = None
        if self.link is not None:
            self.link.abort()
            self.link.close()
            self.link = None

    def _handover_margin(self) -> float:
        """How much earlier than the device's lead a live stream hands blocks over (s): to a
        stream in its own process two blocks more, one it reads ahead (to mark the stream's end)
        and one report period it may wait before writing; in this process none (the stream
        pulls each block when it writes it)."""
        return 2 * self.block if self.opener is not None else 0.0

    def _wire_info(self) -> p.InfoPayload:
        self.open()
        return self.remote.info if self.remote is not None else self.link.info

    @property
    def info(self) -> DeviceInfo:
        """What the device declared when it was opened (opening it if it never was)."""
        if self._info is None:
            w = self._wire_info()
            self._info = DeviceInfo(
                f"usb {self.vid:04x}:{self.pid:04x}",
                p.KINDS[w.kind],
                float(w.rate_hz),
                _shown(w.max_torque),
                _shown(w.encoder_resolution),
                ".".join(str(x) for x in w.firmware),
                w.dynamics(),
                lead=Stream.lead_seconds(w, self.lead, self.block) + self._handover_margin(),
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
        info = self._wire_info()
        blocks = list(program) if isinstance(program, Sequence) else program
        total = sum(map(len, blocks)) / info.rate_hz if isinstance(blocks, list) else None
        rest = iter(blocks)
        first = next(rest, None)
        mask = self._mask(info, first)
        limit = min(np.inf if self.max_torque is None else self.max_torque, info.max_torque)
        program_blocks = chain([] if first is None else [first], rest)
        if self.remote is not None:
            settings = (mask, limit, self.lead, self.block, self.watchdog_ms, hand)
            handed = blocks if isinstance(blocks, list) else program_blocks  # a list goes at once
            tel, dropped, self.underruns = self.remote.play(
                handed, settings, total, progress, monitor
            )
        else:
            here = (mask, limit, hand, total, progress, monitor)
            tel, dropped = self._play_here(program_blocks, *here)
        if dropped:
            names = ", ".join(sorted(dropped))
            tel = _warn(tel, f"the device does not render the {names} layers; they were not sent")
        return tel

    def _play_here(
        self,
        blocks: Iterable[CoefficientBlock],
        mask: int,
        limit: float,
        hand: Hand | None,
        total: float | None,
        progress: Progress | None,
        monitor: Monitor | None,
    ) -> tuple[Telemetry, set[str]]:
        """Stream from this process's thread (a backend given, or told so)."""
        link = self.link
        if hand is not None and hasattr(link.dev.backend, "set_hand"):
            link.dev.backend.set_hand(hand)  # only an emulated device has a hand to set
        stream = Stream(link, mask, limit, self.lead, self.block)
        chunker = Chunker(blocks, p.channel_names(mask))
        try:
            link.set_limits(float(stream.limits[0]), self.watchdog_ms)
            stream.run(chunker, progress, total, monitor)
            link.stop()
        except BaseException:
            link.abort()
            raise
        finally:
            self.underruns = stream.underruns
        tel = stream.telemetry()
        if getattr(link.dev.backend, "realtime", True):  # an emulated device may not be
            tel = replace(tel, lateness=stream.lateness.counts())
        return tel, chunker.dropped

    @staticmethod
    def _mask(info: p.InfoPayload, first: CoefficientBlock | None) -> int:
        """The channels to stream: d alone to a vibrotactile device, else d, k, b (and m)."""
        channels = info.channels
        if not channels & p.CH_K:
            return p.CH_D
        if first is not None and first.m is not None:
            if not channels & p.CH_M:
                raise DeviceError("this USB device cannot render a mass layer")
            return p.ALL_CHANNELS
        return p.CH_D | p.CH_K | p.CH_B


def _number(value: Any) -> bool:
    """True for a finite int or float (not a bool, not text)."""
    return isinstance(value, int | float) and not isinstance(value, bool) and np.isfinite(value)


def _whole(value: Any, lo: int, hi: float) -> bool:
    """True for an int (not a bool) from lo to hi."""
    return isinstance(value, int) and not isinstance(value, bool) and lo <= value <= hi


def _check_options(
    vid: Any,
    pid: Any,
    serial: Any,
    lead: Any,
    block: Any,
    timeout_ms: Any,
    watchdog_ms: Any,
    max_torque: Any,
) -> None:
    """One sentence for an option value the device could not use (before anything opens)."""
    for name, value in (("vid", vid), ("pid", pid)):
        if not _whole(value, 0, 0xFFFF):
            shown = f"{value:#x}" if _whole(value, 0, math.inf) else repr(value)
            raise DeviceError(
                f"the USB {name} is a whole number from 0 to 0xffff (16 bits), not {shown}"
            )
    if serial is not None and not isinstance(serial, str | int):
        raise DeviceError(f"the USB serial is the device's serial number as text, not {serial!r}")
    if max_torque is not None and not (_number(max_torque) and max_torque >= 0):
        raise DeviceError(
            f"the USB max_torque is a torque cap in N*m, 0 (no torque) or more, not {max_torque!r}"
        )
    for name, value in (("lead", lead), ("block", block)):
        if value is not None and not (_number(value) and value > 0):
            raise DeviceError(f"the USB {name} is a positive number of seconds, not {value!r}")
    lo, hi = p.WATCHDOG_RANGE_MS
    if watchdog_ms is not None and not _whole(watchdog_ms, lo, hi):
        raise DeviceError(
            f"the USB watchdog_ms is a whole number from {lo} to {hi}, not {watchdog_ms!r}"
        )
    if not _whole(timeout_ms, 1, math.inf):
        raise DeviceError(f"the USB timeout_ms is a positive whole number, not {timeout_ms!r}")


def _emulating() -> bool:
    return os.environ.get(EMULATE_ENV, "") not in ("", "0")


def _open_hardware(vid: int, pid: int, serial: str | None, timeout_ms: int, _: bool):
    """In the stream's process: the link to a device on the bus, and its backend."""
    backend = default_backend()
    return Link.open(vid, pid, backend, serial, timeout_ms), backend


def _open_emulated(vid: int, pid: int, serial: str | None, timeout_ms: int, realtime: bool):
    """In the stream's process: the link to an emulated device, and its backend."""
    backend = _emulated_backend(vid, pid, realtime)
    return Link.open(vid, pid, backend, serial, timeout_ms), backend


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
