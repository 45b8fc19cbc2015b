"""The `usb` device plugin: a haptic knob or vibrotactile actuator speaking docs/usb-protocol.md."""

from device.usb.driver import UsbKnob

__all__ = ["UsbKnob"]
