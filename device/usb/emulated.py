"""An emulated haptic-timeline USB device that plugs into pyusb as a custom backend.

pyusb's own code (descriptor parsing, configuration, claiming, transfers) runs unchanged on top
of it: `usb.core.find(backend=EmulatedBackend(EmulatedDevice()), ...)`. Behind the endpoints runs
the knob's C firmware (device.usb.firmware) on the `sim` knob's motor and hand. Fault injection
(FaultPlan) makes a transfer time out, an endpoint stall, the device vanish, or the host late
enough to underrun.

Time on the device passes in one of two ways. By default it follows the host: each telemetry
read plays one report's worth of samples, so a stream runs as fast as the host can go (what most
tests want: deterministic, no waiting). With `realtime=True` the firmware's clock is the wall
clock (time.monotonic): before every request the device plays the samples that came due, a
telemetry read waits until a report's worth has played, and a host that hands a block over
after the queue ran dry finds the underrun counted and, past the watchdog, the torque ramped to
zero, as on hardware.
"""

from __future__ import annotations

import array
import errno
import time
from collections.abc import Callable
from dataclasses import dataclass, replace

import numpy as np
import usb.backend
import usb.core
import usb.util

from device.usb import descriptors as desc
from device.usb import protocol as p
from device.usb.firmware import EmulatedKnob
from device.usb.firmware.knob import library
from timeline.plugins.device_protocol import Hand

_GET_DESCRIPTOR = 0x06
_NO_DEVICE = ("No such device (it may have been disconnected)", -4, errno.ENODEV)
_PIPE = ("Pipe error", -9, errno.EPIPE)
_TIMEOUT = ("Operation timed out", -7, errno.ETIMEDOUT)
_OVERFLOW = ("Overflow", -8, errno.EOVERFLOW)


@dataclass(frozen=True)
class FaultPlan:
    """Faults to inject, by index of bulk transfer (0 = the first OUT or IN transfer).

    unplug_after: from this transfer on the device is gone (every request fails with ENODEV).
    timeout_at: this transfer times out (nothing is delivered), once.
    stall_at: this transfer's endpoint halts (EPIPE) until the host clears it.
    late_at: before answering this telemetry read, the device plays out its queue and one more
        report period, as if the host had been descheduled that long (an underrun).
    flip_bit_at: (transfer, bit): this telemetry report arrives with that bit of its bytes
        inverted (a transmission error the CRC must catch).
    lie_at: (transfer, torque): this telemetry report's first torque sample is replaced by the
        value and the report resealed with a valid CRC (firmware reporting garbage: NaN, 1e30).
    """

    unplug_after: int | None = None
    timeout_at: int | None = None
    stall_at: int | None = None
    late_at: int | None = None
    flip_bit_at: tuple[int, int] | None = None
    lie_at: tuple[int, float] | None = None


class WallClock:
    """The firmware's clock in real time: how many servo periods came due since the last look."""

    def __init__(self, rate: float, clock: Callable[[], float] = time.monotonic) -> None:
        self.rate, self.clock = rate, clock
        self.restart()

    def restart(self) -> None:
        """Count from now (time that passes while nothing plays is not owed)."""
        self.anchor, self.ticks = self.clock(), 0

    def due(self) -> int:
        """Periods that have come due and are not played yet."""
        return int((self.clock() - self.anchor) * self.rate) - self.ticks

    def took(self, n: int) -> None:
        """n periods were played (or skipped)."""
        self.ticks += n


class EmulatedDevice:
    """One device on the emulated bus: its firmware, identity, faults and transport state.

    `realtime`: the firmware runs on the wall clock (see the module's docstring); `clock` and
    `sleep` are that clock and how to wait on it (a test may pass a virtual one).
    """

    def __init__(
        self,
        knob: EmulatedKnob | None = None,
        identity: desc.Identity | None = None,
        faults: FaultPlan | None = None,
        record: bool = False,
        realtime: bool = False,
        clock: Callable[[], float] = time.monotonic,
        sleep: Callable[[float], None] = time.sleep,
    ) -> None:
        self.knob = knob or EmulatedKnob()
        self.clock = WallClock(self.knob.info.rate_hz, clock) if realtime else None
        self.sleep = sleep
        self.identity = identity or desc.Identity()
        self.faults = faults or FaultPlan()
        self.record = record
        self.wire_out: list[bytes] = []  # every OUT transfer's bytes, when recording
        self.transfers = 0
        self.unplugged = False
        self.halted: set[int] = set()
        self.configuration = 0
        self.knob.set_identity(self.identity)
        # the firmware's own descriptors, parsed as libusb would (descriptors.py)
        self.device_bytes = self.knob.descriptor(desc.DESC_DEVICE, 0)
        self.config_bytes = self.knob.descriptor(desc.DESC_CONFIGURATION, 0)

    def check_present(self) -> None:
        if self.unplugged:
            raise usb.core.USBError(*_NO_DEVICE)
        self.catch_up()

    def catch_up(self) -> None:
        """Real time: play the periods that came due since the last request.

        Before a stream's first block and while idle nothing is owed: an idle device reports
        at most one report's worth of the time that went by.
        """
        clock, knob = self.clock, self.knob
        if clock is None:
            return
        if knob.waiting:
            clock.restart()
            return
        n = clock.due()
        if knob.state == p.STATE_IDLE and n > knob.info.report_samples:
            clock.took(n - knob.info.report_samples)
            n = knob.info.report_samples
        if n > 0:
            knob.advance_samples(n)
            clock.took(n)

    def telemetry_report(self) -> bytes:
        """The next report: after one report's worth of samples played (waiting for them in
        real time)."""
        if self.clock is None:
            return self.knob.send()
        need = self.knob.info.report_samples
        while self.knob.unreported < need and not self.knob.waiting:
            self.sleep((need - self.knob.unreported) / self.clock.rate)
            self.catch_up()
        return self.knob.report()

    def next_transfer(self, ep: int) -> int:
        """Count a bulk transfer and raise the fault planned for it, if any."""
        self.check_present()
        i = self.transfers
        self.transfers += 1
        f = self.faults
        if f.unplug_after is not None and i >= f.unplug_after:
            self.unplugged = True
            raise usb.core.USBError(*_NO_DEVICE)
        if i == f.stall_at:
            self.halted.add(ep)
        if ep in self.halted:
            raise usb.core.USBError(*_PIPE)
        if i == f.timeout_at:
            raise usb.core.USBTimeoutError(*_TIMEOUT)
        return i


def _damaged(payload: bytes, i: int, faults: FaultPlan) -> bytes:
    """A telemetry report with the damage planned for transfer i, if any."""
    if faults.flip_bit_at is not None and faults.flip_bit_at[0] == i:
        bit = faults.flip_bit_at[1] % (8 * len(payload))
        damaged = bytearray(payload)
        damaged[bit // 8] ^= 1 << (bit % 8)
        return bytes(damaged)
    if faults.lie_at is not None and faults.lie_at[0] == i:
        report = p.decode_report(payload)
        samples = np.array(report.samples, dtype=np.float32)
        if len(samples):
            samples[0, 2] = faults.lie_at[1]
        return p.encode_report(replace(report, samples=samples))
    return payload


class EmulatedBackend(usb.backend.IBackend):
    """A pyusb backend whose bus holds the given emulated devices."""

    def __init__(self, *devices: EmulatedDevice) -> None:
        super().__init__()
        self.devices = list(devices)

    def warm_up(self) -> None:
        """Load the compiled firmware (each device already did: nothing is left to load while
        the wall clock runs)."""
        library()

    @property
    def realtime(self) -> bool:
        """True when the devices run on the wall clock (their lateness is real)."""
        return any(dev.clock is not None for dev in self.devices)

    def set_hand(self, hand: Hand) -> None:
        """What the (emulated) user's hand does from the next START on."""
        for dev in self.devices:
            dev.knob.hand = hand

    # --- enumeration and descriptors -----------------------------------------------------------
    def enumerate_devices(self) -> list[EmulatedDevice]:
        return [d for d in self.devices if not d.unplugged]

    def get_parent(self, dev: EmulatedDevice) -> None:
        return None

    def get_device_descriptor(self, dev: EmulatedDevice) -> object:
        address = self.devices.index(dev) + 1
        return desc.parse_device(dev.device_bytes, address, 1, dev.identity.high_speed)

    def get_configuration_descriptor(self, dev: EmulatedDevice, config: int) -> object:
        if config != 0:
            raise IndexError(config)
        return desc.parse_configuration(dev.config_bytes)

    def get_interface_descriptor(self, dev: EmulatedDevice, intf: int, alt: int, config: int):
        if (intf, alt, config) != (0, 0, 0):
            raise IndexError((intf, alt, config))
        return desc.parse_interface(dev.config_bytes)

    def get_endpoint_descriptor(self, dev: EmulatedDevice, ep: int, intf: int, alt: int, config):
        if (intf, alt, config) != (0, 0, 0):
            raise IndexError((intf, alt, config))
        return desc.parse_endpoint(dev.config_bytes, ep)

    # --- handles ---------------------------------------------------------------------------------
    def open_device(self, dev: EmulatedDevice) -> EmulatedDevice:
        dev.check_present()
        return dev

    def close_device(self, dev_handle: EmulatedDevice) -> None:
        return None

    def set_configuration(self, dev_handle: EmulatedDevice, config_value: int) -> None:
        dev_handle.check_present()
        if config_value not in (0, 1):
            raise usb.core.USBError(*_PIPE)
        dev_handle.configuration = config_value

    def get_configuration(self, dev_handle: EmulatedDevice) -> int:
        dev_handle.check_present()
        return dev_handle.configuration

    def set_interface_altsetting(self, dev_handle: EmulatedDevice, intf: int, alt: int) -> None:
        dev_handle.check_present()
        if (intf, alt) != (0, 0):
            raise usb.core.USBError(*_PIPE)

    def claim_interface(self, dev_handle: EmulatedDevice, intf: int) -> None:
        dev_handle.check_present()
        if intf != p.INTERFACE_NUMBER:
            raise usb.core.USBError("Entity not found", -5, errno.ENOENT)

    def release_interface(self, dev_handle: EmulatedDevice, intf: int) -> None:
        dev_handle.check_present()

    def is_kernel_driver_active(self, dev_handle: EmulatedDevice, intf: int) -> bool:
        return False

    def clear_halt(self, dev_handle: EmulatedDevice, ep: int) -> None:
        dev_handle.check_present()
        dev_handle.halted.discard(ep)

    # --- transfers -------------------------------------------------------------------------------
    def bulk_write(self, dev_handle: EmulatedDevice, ep: int, intf: int, data, timeout: int) -> int:
        dev_handle.next_transfer(ep)
        if ep != p.EP_OUT:
            raise usb.core.USBError(*_PIPE)
        payload = bytes(data)
        if dev_handle.record:
            dev_handle.wire_out.append(payload)
        dev_handle.knob.receive(payload)
        return len(payload)

    def bulk_read(self, dev_handle: EmulatedDevice, ep: int, intf: int, buff, timeout: int) -> int:
        i = dev_handle.next_transfer(ep)
        if ep != p.EP_IN:
            raise usb.core.USBError(*_PIPE)
        if i == dev_handle.faults.late_at:
            dev_handle.knob.starve()
        payload = _damaged(dev_handle.telemetry_report(), i, dev_handle.faults)
        if len(payload) > len(buff) * buff.itemsize:
            raise usb.core.USBError(*_OVERFLOW)
        buff[: len(payload)] = array.array("B", payload)
        return len(payload)

    def ctrl_transfer(
        self,
        dev_handle: EmulatedDevice,
        bmRequestType: int,
        bRequest: int,
        wValue: int,
        wIndex: int,
        data,
        timeout: int,
    ) -> int:
        dev_handle.check_present()
        try:
            if bmRequestType == 0x80 and bRequest == _GET_DESCRIPTOR:
                answer = self._descriptor(dev_handle, wValue >> 8, wValue & 0xFF)
            elif bmRequestType == p.REQUEST_TYPE_IN and wIndex == p.INTERFACE_NUMBER:
                answer = dev_handle.knob.control_in(bRequest, len(data))
            elif bmRequestType == p.REQUEST_TYPE_OUT and wIndex == p.INTERFACE_NUMBER:
                dev_handle.knob.control_out(bRequest, wValue, bytes(data))
                return len(data)
            else:
                raise p.ProtocolError(f"unsupported request {bmRequestType:#x}/{bRequest:#x}")
        except (p.ProtocolError, IndexError):
            raise usb.core.USBError(*_PIPE) from None
        n = min(len(answer), len(data))
        data[:n] = array.array("B", answer[:n])
        return n

    @staticmethod
    def _descriptor(dev: EmulatedDevice, kind: int, index: int) -> bytes:
        if kind == desc.DESC_DEVICE:
            return dev.device_bytes
        if kind == desc.DESC_CONFIGURATION and index == 0:
            return dev.config_bytes
        if kind == desc.DESC_STRING:
            return dev.knob.descriptor(kind, index)
        raise IndexError(kind)
