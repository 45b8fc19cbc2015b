"""The knob's C firmware (device/usb/firmware/ht_fw.c): its bytes are the protocol module's, its
servo loop is the simulated knob's, and it plays exported position tables with no host.

Tolerance against the sim: 1e-9 of each channel's largest magnitude, in float64 (the C loop's
own numbers, before the wire's float32). Measured: angle and torque equal bit for bit (the same
arithmetic in the same order, compiled without fused multiply-adds), velocity within 9e-16 rad/s
(the sim's telemetry recomputes it in lfilter's form).
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from device.sim import SimKnob
from device.usb import UsbKnob
from device.usb import descriptors as desc
from device.usb import protocol as p
from device.usb.emulated import EmulatedBackend, EmulatedDevice
from device.usb.firmware import EmulatedKnob
from timeline.files.projectfile import load
from timeline.plugins.device_protocol import CoefficientBlock, Hand, PositionTable
from timeline.rendering.playback import prepare

PROJECTS = Path(__file__).resolve().parents[2] / "projects"


def close(c_loop: np.ndarray, sim: np.ndarray) -> bool:
    """Equal to 1e-9 of the largest magnitude (relative to the channel's scale)."""
    scale = max(float(np.abs(sim).max()), 1e-300)
    return c_loop.shape == sim.shape and float(np.abs(c_loop - sim).max()) <= 1e-9 * scale


def f32(blocks: list[CoefficientBlock]) -> list[CoefficientBlock]:
    r = lambda a: None if a is None else a.astype(np.float32).astype(np.float64)  # noqa: E731
    return [CoefficientBlock(r(x.d), r(x.k), r(x.b), r(x.m)) for x in blocks]


@pytest.mark.parametrize(
    "knob", [{}, {"declare_estimator": False}, {"vibrotactile": True}], ids=str
)
def test_the_c_get_info_answer_is_the_protocol_modules(knob: dict) -> None:
    firmware = EmulatedKnob(**knob)
    size = p.INFO_SIZE if firmware.info.protocol_minor else p.INFO_V20_SIZE
    assert firmware.control_in(p.REQ_GET_INFO, 200) == p.encode_info(firmware.info)
    assert len(firmware.control_in(p.REQ_GET_INFO, 200)) == size
    assert firmware.control_in(p.REQ_GET_INFO, 58) == p.encode_info(firmware.info)[:58]
    with pytest.raises(p.ProtocolError):
        firmware.control_in(p.REQ_GET_INFO, 57)


@pytest.mark.parametrize("high_speed", [False, True])
def test_the_c_descriptors_are_the_documented_bytes(high_speed: bool) -> None:
    ident = desc.Identity(0x1209, 0x0D32, "Acme", "Knob Ü", "SN-42", high_speed)
    firmware = EmulatedKnob()
    firmware.set_identity(ident)
    assert firmware.descriptor(desc.DESC_DEVICE, 0) == desc.device_descriptor(ident)
    assert firmware.descriptor(desc.DESC_CONFIGURATION, 0) == desc.configuration_descriptor(ident)
    for index in range(4):
        assert firmware.descriptor(desc.DESC_STRING, index) == desc.string_descriptor(ident, index)
    with pytest.raises(IndexError):
        firmware.descriptor(desc.DESC_STRING, 4)


@pytest.mark.parametrize(
    ("name", "hand"), [("rising_resistance.htl", "turn:90"), ("notification_buzz.htl", "hold")]
)
def test_the_c_loop_equals_the_simulated_knob_on_the_example_projects(name, hand) -> None:
    firmware = EmulatedKnob()
    usb = UsbKnob(backend=EmulatedBackend(EmulatedDevice(firmware)))
    blocks = f32(prepare(load(PROJECTS / name), usb.info, hand=Hand.parse(hand)).program)
    n = sum(len(b) for b in blocks)
    firmware.record_trace(n)
    usb.play(blocks, Hand.parse(hand))
    sim = SimKnob(delay=1, gains=firmware.info.observer_gains).play(blocks, Hand.parse(hand))
    trace = firmware.trace
    assert len(trace) == len(sim) == n and np.abs(sim.torque).max() > 0.01
    for column, channel in enumerate(("angle", "velocity", "torque")):
        assert close(trace[:, column], getattr(sim, channel)), channel


def test_position_mode_plays_the_fan_knobs_tables_as_the_sim_does() -> None:
    """No host: the tables looked up at the angle the encoder reads, turned by a hand."""
    firmware = EmulatedKnob()
    program = prepare(load(PROJECTS / "fan_knob.htl"), UsbKnob(
        backend=EmulatedBackend(EmulatedDevice(firmware))).info, duration=0.5).program  # fmt: skip
    table = program.table
    as32 = {name: getattr(table, name).astype(np.float32) for name in ("torque", "damping", "mass")
            if getattr(table, name) is not None}  # fmt: skip
    rounded = PositionTable(table.start, table.rate, *(
        None if getattr(table, k) is None else as32[k].astype(np.float64)
        for k in ("torque", "damping", "mass")))  # fmt: skip
    hand = Hand.parse("turn:180")
    n = 5000
    firmware.hand = hand
    firmware.record_trace(n)
    firmware.play_table(as32, table.start, table.rate, program.origin)
    firmware.advance_samples(n)
    sim = SimKnob(delay=1, gains=firmware.info.observer_gains).play(
        replace(program, table=rounded, duration=n / 10_000), hand
    )
    trace = firmware.trace
    assert abs(sim.angle[-1]) > 0.1 and np.abs(sim.torque).max() > 0.01  # it turned, felt it
    for column, channel in enumerate(("angle", "velocity", "torque")):
        assert close(trace[:, column], getattr(sim, channel)), channel
    firmware.control_out(p.REQ_STOP, 0, b"")
    firmware.advance(0.0102)  # the ramp, its zero sample, the one-period delay
    assert (firmware.state, firmware.torque) == (p.STATE_IDLE, 0.0)
