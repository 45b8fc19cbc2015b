"""The knob's firmware: portable C (ht_fw.c, docs/firmware.md) that the emulated device runs.

`EmulatedKnob` is that C firmware compiled for the host (build.py) behind ctypes, its HAL
stepping the simulated motor and hand (ports/sim/ht_sim.c with device/sim's plant).
"""

from device.usb.firmware.knob import FIRMWARE_VERSION, EmulatedKnob

__all__ = ["FIRMWARE_VERSION", "EmulatedKnob"]
