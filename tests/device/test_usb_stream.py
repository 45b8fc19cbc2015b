"""Streaming through pyusb to the emulated device: sim-equal telemetry, safety and faults.

Tolerance against the sim: zero. The wire carries float32, so the reference is the sim device
fed the same float32-rounded coefficients, and its angle, velocity and torque rounded to float32
must equal what the device reported bit for bit; saturation, layers and stability flags equal.
Energy is the exception: the host estimates it from the encoder and the friction GET_INFO
declares, where the sim integrates the true angle; it must agree to 0.1 % of the motor's total
|work| (measured: at worst 0.013 %, on notification_buzz held).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from device.sim import KnobParams, SimKnob
from device.usb import UsbKnob
from device.usb import protocol as p
from device.usb.emulated import EmulatedBackend, EmulatedDevice, FaultPlan
from device.usb.errors import (
    DeviceFault,
    DeviceTimeout,
    DeviceUnderrun,
    DeviceUnplugged,
    EndpointStalled,
    UsbDeviceError,
)
from device.usb.firmware import EmulatedKnob
from timeline.files.projectfile import load
from timeline.plugins.device_protocol import (
    CoefficientBlock,
    DeviceError,
    Hand,
    PositionProgram,
    PositionTable,
    Telemetry,
)
from timeline.rendering.playback import prepare

PROJECTS = Path(__file__).resolve().parents[2] / "projects"
RATE = 10_000


def rig(knob: EmulatedKnob | None = None, faults: FaultPlan | None = None, **options):
    """A UsbKnob talking to one emulated device that records the OUT transfers."""
    emulated = EmulatedDevice(knob, faults=faults, record=True)
    return UsbKnob(backend=EmulatedBackend(emulated), **options), emulated


def blocks_of(n: int, d=0.0, k=0.0, b=0.0, m=None, size: int = 1000) -> list[CoefficientBlock]:
    t = np.arange(n) / RATE
    full = [None if v is None else np.broadcast_to(v(t) if callable(v) else v, (n,)).astype(float)
            for v in (d, k, b, m)]  # fmt: skip
    return [CoefficientBlock(*(None if a is None else a[i : i + size] for a in full))
            for i in range(0, n, size)]  # fmt: skip


def float32_blocks(blocks: list[CoefficientBlock]) -> list[CoefficientBlock]:
    r = lambda a: None if a is None else a.astype(np.float32).astype(np.float64)  # noqa: E731
    return [CoefficientBlock(r(x.d), r(x.k), r(x.b), r(x.m)) for x in blocks]


def f32(a: np.ndarray) -> np.ndarray:
    return a.astype(np.float32).astype(np.float64)


def wire(emulated: EmulatedDevice) -> list[p.Block]:
    return [p.decode_block(data) for data in emulated.wire_out]


def assert_same_as_sim(usb: Telemetry, sim: Telemetry) -> None:
    assert len(usb) == len(sim)
    for name in ("angle", "velocity", "torque"):
        assert np.array_equal(getattr(usb, name), f32(getattr(sim, name))), name
    assert np.array_equal(usb.time, sim.time)
    assert np.array_equal(usb.saturated, sim.saturated)
    assert usb.layers.keys() == sim.layers.keys()
    for name, values in sim.layers.items():
        assert np.array_equal(usb.layers[name], values), name
    assert [(f.kind, f.times.tolist()) for f in usb.flags] == [
        (f.kind, f.times.tolist()) for f in sim.flags
    ]
    motor_work = np.sum(np.abs(sim.torque * np.diff(sim.angle, append=sim.angle[-1])))
    assert np.abs(usb.energy - sim.energy).max() <= 1e-3 * motor_work


def test_a_project_streamed_over_usb_reports_the_sim_telemetry() -> None:
    project = load(PROJECTS / "rising_resistance.htl")
    hand = Hand.parse("turn:90")
    knob, emulated = rig()
    blocks = float32_blocks(prepare(project, knob.info, hand=hand).program)
    usb = knob.play(blocks, hand)
    sim = SimKnob(delay=1).play(blocks, hand)
    assert len(usb) == 20_000 and usb.time_saturated > 0.5  # the clamp was exercised
    assert_same_as_sim(usb, sim)
    sent = wire(emulated)
    assert [b.seq for b in sent] == list(range(len(sent)))
    assert [b.end for b in sent] == [False] * (len(sent) - 1) + [True]
    assert {b.mask for b in sent} == {p.CH_D | p.CH_K | p.CH_B}
    assert all(len(data) % 64 and len(data) <= p.block_bytes(100, 7) for data in emulated.wire_out)
    stream = np.concatenate([b.samples for b in sent])
    assert np.array_equal(stream, np.column_stack([usb.layers[x] for x in "dkb"]))
    assert emulated.knob.underruns == emulated.knob.overruns == emulated.knob.flags == 0


def test_the_device_ends_a_finished_stream_at_zero_torque() -> None:
    knob, emulated = rig()
    tel = knob.play(blocks_of(2000, d=0.05, k=0.5), Hand("hold"))
    assert tel.torque[-1] == pytest.approx(0.05 / 1.5, rel=0.01)  # d - k*d/(k + grip)
    assert emulated.knob.state == p.STATE_RAMPING  # STOP sent: ramping over 10 ms
    emulated.knob.advance(0.0102)  # the 10 ms ramp, its zero sample, one period of delay
    assert (emulated.knob.state, emulated.knob.torque) == (p.STATE_IDLE, 0.0)


def test_a_mass_layer_streams_all_four_coefficients() -> None:
    blocks = float32_blocks(
        blocks_of(3000, d=lambda t: 0.03 * np.sin(2 * np.pi * 15 * t), k=0.4, b=2e-4, m=2e-6)
    )
    knob, emulated = rig()
    usb = knob.play(blocks, Hand("free"))
    # the same firmware: the float32 observer gains it declares and runs
    sim = SimKnob(delay=1, gains=emulated.knob.info.observer_gains)
    assert_same_as_sim(usb, sim.play(blocks, Hand("free")))
    assert {b.mask for b in wire(emulated)} == {p.ALL_CHANNELS}
    assert len(emulated.wire_out[0]) == 1616  # 10 ms of four float32 channels, header, CRC


def test_a_small_device_buffer_is_never_overrun() -> None:
    """Capacity 250 samples, blocks of at most 50: the host's lead shrinks to fit."""
    small = EmulatedKnob(buffer_capacity=250, max_block=50)
    knob, emulated = rig(small)
    blocks = float32_blocks(blocks_of(4000, d=lambda t: 0.05 * np.sin(2 * np.pi * 5 * t), k=3.0))
    usb = knob.play(blocks, Hand("hold"))
    assert_same_as_sim(usb, SimKnob(delay=1).play(blocks, Hand("hold")))
    assert usb.flag("passivity").count == 4000  # k = 3 is above K_pass = 2 N*m/rad
    assert max(len(b.samples) for b in wire(emulated)) <= 50
    assert small.overruns == small.underruns == 0


def test_a_buffer_too_small_for_a_report_is_refused_in_one_sentence() -> None:
    knob, _ = rig(EmulatedKnob(buffer_capacity=120, max_block=50))
    with pytest.raises(UsbDeviceError, match=r"buffer \(120 samples\) cannot hold a telemetry"):
        knob.play(blocks_of(1000, d=0.01))


STEADY = dict(d=0.05, k=0.5)  # held by a 1 N*m/rad grip: about 33 mNm at any failure


@pytest.mark.parametrize(
    "faults, error, words",
    # Transfers 0-2 prime the queue; from 3 on, reads (odd) and writes (even) alternate.
    [
        (FaultPlan(timeout_at=10), DeviceTimeout, r"did not answer within 1000 ms while streaming"),
        (FaultPlan(stall_at=9), EndpointStalled, r"stalled endpoint 0x81 .* reading telemetry"),
        (FaultPlan(late_at=11), DeviceUnderrun, r"ran out of samples at .* host fell behind"),
        (FaultPlan(flip_bit_at=(9, 900)), UsbDeviceError, r"CRC-32 does not match its bytes"),
        (FaultPlan(flip_bit_at=(9, 7)), UsbDeviceError, r"CRC-32 does not match its bytes"),
        (FaultPlan(lie_at=(9, math.nan)), DeviceFault, r"impossible sample .* torque nan N\*m"),
        (FaultPlan(lie_at=(9, 1e30)), DeviceFault, r"impossible sample .* torque 1e\+30 N\*m"),
        (FaultPlan(lie_at=(9, -0.2)), DeviceFault, r"torque -0.2 N\*m; limit 0.18 N\*m"),
    ],
)
def test_a_failure_stops_the_device_and_says_why_in_one_sentence(faults, error, words) -> None:
    knob, emulated = rig(faults=faults)
    with pytest.raises(error, match=words) as err:
        knob.play(blocks_of(5000, **STEADY), Hand("hold"))
    assert "\n" not in str(err.value)
    device = emulated.knob
    assert device.state == p.STATE_RAMPING and abs(device.torque) > 0.03  # STOP arrived
    device.advance(0.0102)  # the 10 ms ramp, its zero sample, one period of delay
    assert (device.state, device.torque) == (p.STATE_IDLE, 0.0)
    assert emulated.halted == set()  # a stalled endpoint was cleared
    again = knob.play(blocks_of(1000, d=0.02), Hand("hold"))  # and the device plays again
    assert len(again) == 1000


def test_an_unplugged_device_is_reported_and_its_watchdog_zeroes_the_torque() -> None:
    knob, emulated = rig(faults=FaultPlan(unplug_after=11))
    with pytest.raises(DeviceUnplugged, match=r"^the USB haptic device was unplugged while"):
        knob.play(blocks_of(5000, **STEADY), Hand("hold"))
    device = emulated.knob
    assert device.state == p.STATE_RUNNING and abs(device.torque) > 0.03  # nobody said STOP
    device.advance(0.050 + 0.0102)  # watchdog + ramp after the last block, at most
    assert (device.state, device.torque) == (p.STATE_IDLE, 0.0)
    assert device.flags & p.FLAG_WATCHDOG
    assert UsbKnob.discover(backend=knob.backend) == []  # gone from the bus


def test_a_device_reporting_a_lower_max_torque_is_respected() -> None:
    drive = lambda t: 0.1 * np.sin(2 * np.pi * 10 * t)  # noqa: E731 - twice what it allows
    weak = KnobParams(max_torque=0.05)
    knob, emulated = rig(EmulatedKnob(weak))
    blocks = blocks_of(2000, d=drive)
    usb = knob.play(blocks, Hand("hold"))
    limit = np.float32(0.05)
    d_sent = np.concatenate([b.samples[:, 0] for b in wire(emulated)])
    assert d_sent.max() == limit and d_sent.min() == -limit
    assert np.abs(usb.torque).max() == limit and usb.saturated.any()
    over = np.count_nonzero(np.abs(np.concatenate([b.d for b in blocks])) > limit)
    assert over == 1332  # |sin| > 1/2 for two thirds of the samples
    assert usb.warnings == (
        f"{over} values were clamped to the device's limits (max torque 50 mNm)",
    )
    clamped = [
        CoefficientBlock(f32(np.clip(b.d, -limit, limit)), f32(b.k), f32(b.b)) for b in blocks
    ]
    assert_same_as_sim(usb, SimKnob(max_torque=0.05).play(clamped, Hand("hold")))


def test_a_lower_host_limit_is_sent_to_the_device() -> None:
    knob, emulated = rig(max_torque=0.03)
    usb = knob.play(blocks_of(1000, d=0.1), Hand("hold"))
    assert emulated.knob.torque_limit == pytest.approx(0.03)
    assert np.abs(usb.torque).max() == np.float32(0.03)


def test_nan_and_inf_never_reach_the_wire() -> None:
    blocks = blocks_of(1000, d=0.02, k=0.3)
    blocks[0].d[100] = math.nan
    blocks[0].k[200] = -math.inf
    knob, emulated = rig()
    usb = knob.play(blocks, Hand("hold"))
    stream = np.concatenate([b.samples for b in wire(emulated)])
    assert np.isfinite(stream).all()
    assert stream[100].tolist() == stream[200].tolist() == [0.0, 0.0, 0.0]
    # the zeros are applied one period later (the knob firmware's computation delay)
    assert usb.torque[101] == usb.torque[201] == 0.0 and usb.torque[102] != 0.0
    assert "2 samples held NaN or infinite values and were sent as zero" in usb.warnings
    assert not emulated.knob.flags & p.FLAG_NON_FINITE  # the host cleaned them first


def test_a_vibrotactile_device_receives_the_drive_term_only() -> None:
    blocks = blocks_of(1000, d=lambda t: 1.5 * np.sin(2 * np.pi * 175 * t), k=0.5)
    knob, emulated = rig(EmulatedKnob(vibrotactile=True))
    usb = knob.play(blocks, Hand("hold"))
    sent = wire(emulated)
    assert {b.mask for b in sent} == {p.CH_D} and len(emulated.wire_out[0]) == 12 + 4 * 100 + 4
    expected = f32(np.clip(blocks[0].d, -1.0, 1.0))
    assert np.array_equal(usb.torque, expected) and np.array_equal(usb.layers["d"], expected)
    assert not usb.angle.any() and not usb.velocity.any()
    assert "the device does not render the k layers; they were not sent" in usb.warnings


def test_progress_reports_seconds_played_out_of_the_total() -> None:
    calls = []
    knob, _ = rig()
    knob.play(blocks_of(3000, d=0.01), Hand("hold"), lambda s, total: calls.append((s, total)))
    assert calls[-1] == (0.3, 0.3)
    assert [s for s, _ in calls] == sorted(s for s, _ in calls)


def test_a_position_program_is_refused_and_an_empty_one_plays_nothing() -> None:
    knob, emulated = rig()
    table = PositionTable(0.0, 100.0, np.zeros(10))
    with pytest.raises(DeviceError, match="time-mode coefficient blocks"):
        knob.play(PositionProgram(table, 1.0))
    assert len(knob.play([])) == 0 and emulated.wire_out == []


def test_a_report_that_breaks_the_protocol_stops_the_device(monkeypatch) -> None:
    knob, emulated = rig()
    monkeypatch.setattr(emulated.knob, "send", lambda: b"HT\x07" + bytes(40))
    with pytest.raises(UsbDeviceError, match=r"sent a telemetry report that breaks the protocol"):
        knob.play(blocks_of(2000, **STEADY), Hand("hold"))
    assert emulated.knob.state == p.STATE_RAMPING


def test_a_play_the_device_clamped_finishes_and_says_so_in_its_summary() -> None:
    """A stiff spring under a turning hand asks for more than 50 mNm: the device clamps it (its
    SATURATED flag, the safe behaviour), the play runs to its end and its summary says so."""
    knob, _ = rig(EmulatedKnob(KnobParams(max_torque=0.05)))
    usb = knob.play(blocks_of(2000, k=5.0), Hand.parse("turn:90"))
    assert len(usb) == 2000
    assert np.abs(usb.torque).max() == np.float32(0.05)
    line = next(line for line in usb.summary() if line.startswith("saturated"))
    assert line == (
        f"saturated {usb.time_saturated:.4f} s: the device clamped its output to its limit there, "
        "and the play went on"
    )
    assert usb.time_saturated > 0.01
