"""What can go wrong with a USB haptic device, each as one sentence for the user."""

from __future__ import annotations

from timeline.plugins.device_protocol import DeviceError


class UsbDeviceError(DeviceError):
    """A USB haptic device is missing or failed while playing."""


class DeviceNotFound(UsbDeviceError):
    """No device with the requested VID:PID is attached."""


class DeviceUnplugged(UsbDeviceError):
    """The device disappeared from the bus."""


class DeviceTimeout(UsbDeviceError):
    """A transfer did not complete in time."""


class EndpointStalled(UsbDeviceError):
    """The device halted an endpoint (refused a transfer)."""


class DeviceUnderrun(UsbDeviceError):
    """The device's queue ran empty while playing."""


class DeviceFault(UsbDeviceError):
    """The device reported a fault flag (watchdog, overrun, sequence, bad block)."""
