"""An open connection to one haptic-timeline USB device through pyusb.

Finds the device, checks its interface, and wraps every request of the protocol; each pyusb
failure becomes one sentence (device.usb.errors) naming what the host was doing.
"""

from __future__ import annotations

import errno
from collections.abc import Callable
from contextlib import suppress
from typing import Any, TypeVar

import usb.core
import usb.util

from device.usb import protocol as p
from device.usb.errors import (
    DeviceNotFound,
    DeviceTimeout,
    DeviceUnplugged,
    EndpointStalled,
    UsbDeviceError,
)

T = TypeVar("T")
_LIBUSB_NO_DEVICE, _LIBUSB_PIPE, _LIBUSB_ACCESS = -4, -9, -3


def default_backend() -> Any:
    """libusb from the libusb-package wheel when installed, else the system's libusb-1.0.

    None when neither can be loaded.
    """
    try:
        import libusb_package
    except ImportError:
        import usb.backend.libusb1

        return usb.backend.libusb1.get_backend()
    return libusb_package.get_libusb1_backend()


def is_haptic(dev: usb.core.Device) -> bool:
    """True when the device's first interface is this protocol's vendor interface."""
    try:
        intf = dev[0][(p.INTERFACE_NUMBER, 0)]
    except (usb.core.USBError, IndexError, KeyError):
        return False
    return (intf.bInterfaceClass, intf.bInterfaceSubClass, intf.bInterfaceProtocol) == (
        p.INTERFACE_CLASS,
        p.INTERFACE_SUBCLASS,
        p.INTERFACE_PROTOCOL,
    )


def find_devices(vid: int, pid: int, backend: Any = None) -> list[usb.core.Device]:
    """Every attached haptic-timeline device with this VID:PID (UsbDeviceError without libusb)."""
    try:
        found = list(usb.core.find(find_all=True, idVendor=vid, idProduct=pid, backend=backend))
    except usb.core.NoBackendError:
        raise UsbDeviceError(
            "no USB library was found: install libusb (apt-get install libusb-1.0-0) or "
            "pip install libusb-package"
        ) from None
    except usb.core.USBError as exc:
        raise UsbDeviceError(f"cannot list USB devices: {exc.strerror or exc}") from None
    return [dev for dev in found if is_haptic(dev)]


class Link:
    """The host's end of the protocol for one opened device."""

    def __init__(self, dev: usb.core.Device, timeout_ms: int = 1000) -> None:
        self.dev = dev
        self.timeout_ms = timeout_ms
        self._call("opening the device", self._configure)
        raw = self._call(
            "reading the device info",
            dev.ctrl_transfer,
            p.REQUEST_TYPE_IN,
            p.REQ_GET_INFO,
            0,
            p.INTERFACE_NUMBER,
            p.INFO_SIZE,
            timeout_ms,
        )
        self.info = _decoded(p.decode_info, raw, "device info")

    @classmethod
    def open(
        cls,
        vid: int,
        pid: int,
        backend: Any = None,
        serial: str | None = None,
        timeout_ms: int = 1000,
    ) -> Link:
        """Open the first matching device (with this serial number, when given)."""
        for dev in find_devices(vid, pid, backend):
            if serial is None or _serial(dev) == serial:
                return cls(dev, timeout_ms)
        which = f"{vid:04x}:{pid:04x}" + (f" with serial {serial}" if serial else "")
        raise DeviceNotFound(
            f"no USB haptic device {which} found (check the cable and permissions, or use the "
            f"sim device)"
        )

    def _configure(self) -> None:
        try:
            active = self.dev.get_active_configuration().bConfigurationValue
        except usb.core.USBError:
            active = 0
        if active != 1:
            self.dev.set_configuration(1)
        usb.util.claim_interface(self.dev, p.INTERFACE_NUMBER)

    # --- requests -------------------------------------------------------------------------------
    def set_limits(self, max_torque: float, watchdog_ms: int) -> None:
        data = p.encode_limits(max_torque, watchdog_ms)
        self._control("setting limits", p.REQ_SET_LIMITS, 0, data)

    def start(self, mask: int) -> None:
        self._control("starting the stream", p.REQ_START, mask, None)

    def stop(self) -> None:
        self._control("stopping", p.REQ_STOP, 0, None)

    def write_block(self, block: p.Block) -> None:
        data = p.encode_block(block)
        self._call("streaming", self.dev.write, p.EP_OUT, data, self.timeout_ms, ep=p.EP_OUT)

    def read_report(self) -> p.Report:
        size = p.report_bytes(self.info.report_samples)
        data = self._call(
            "reading telemetry", self.dev.read, p.EP_IN, size, self.timeout_ms, ep=p.EP_IN
        )
        return _decoded(p.decode_report, data, "a telemetry report")

    def abort(self) -> None:
        """After a failure: STOP, then clear halted endpoints; ignore a device that is gone."""
        with suppress(UsbDeviceError):
            self.stop()
        for ep in (p.EP_OUT, p.EP_IN):
            with suppress(usb.core.USBError):
                self.dev.clear_halt(ep)

    def close(self) -> None:
        """Release the interface and the handle (the device's state is left as it is)."""
        with suppress(usb.core.USBError):
            usb.util.dispose_resources(self.dev)

    # --- errors ---------------------------------------------------------------------------------
    def _control(self, what: str, request: int, value: int, data: bytes | None) -> None:
        self._call(
            what,
            self.dev.ctrl_transfer,
            p.REQUEST_TYPE_OUT,
            request,
            value,
            p.INTERFACE_NUMBER,
            data,
            self.timeout_ms,
            ep=0,
        )

    def _call(self, what: str, fn: Callable[..., T], *args: Any, ep: int = 0) -> T:
        try:
            return fn(*args)
        except usb.core.USBTimeoutError:
            raise DeviceTimeout(
                f"the USB haptic device did not answer within {self.timeout_ms} ms while {what}, "
                "so playback stopped"
            ) from None
        except usb.core.USBError as exc:
            raise _usb_error(exc, what, ep) from None


def _usb_error(exc: usb.core.USBError, what: str, ep: int) -> UsbDeviceError:
    code = exc.backend_error_code
    if exc.errno == errno.ENODEV or code == _LIBUSB_NO_DEVICE:
        return DeviceUnplugged(
            f"the USB haptic device was unplugged while {what}; "
            "its watchdog ramps the torque to zero"
        )
    if exc.errno == errno.EPIPE or code == _LIBUSB_PIPE:
        return EndpointStalled(
            f"the USB haptic device stalled endpoint {ep:#04x} (refused the request) while {what}, "
            "so playback stopped"
        )
    if exc.errno == errno.EACCES or code == _LIBUSB_ACCESS:
        return UsbDeviceError(
            f"permission denied while {what}: allow access to the USB device (a udev rule) or run "
            "as a user who may"
        )
    return UsbDeviceError(f"the USB transfer failed while {what}: {exc.strerror or exc}")


def _decoded(decode: Callable[[bytes], T], data: bytes, what: str) -> T:
    try:
        return decode(data)
    except p.ProtocolError as exc:
        raise UsbDeviceError(
            f"the USB haptic device sent {what} that breaks the protocol ({exc})"
        ) from None


def _serial(dev: usb.core.Device) -> str | None:
    try:
        return dev.serial_number
    except (usb.core.USBError, ValueError):
        return None
