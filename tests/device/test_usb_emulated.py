"""The emulated device seen through pyusb's real descriptor parsing and control transfers."""

from __future__ import annotations

import errno
import math

import numpy as np
import pytest
import usb.core
import usb.util

from device.sim import KnobParams
from device.usb import UsbKnob
from device.usb import protocol as p
from device.usb.descriptors import Identity
from device.usb.emulated import EmulatedBackend, EmulatedDevice
from device.usb.errors import DeviceNotFound
from device.usb.firmware import EmulatedKnob


def found(*devices: EmulatedDevice, **match: int) -> usb.core.Device:
    dev = usb.core.find(backend=EmulatedBackend(*devices), **match)
    assert dev is not None
    return dev


@pytest.mark.parametrize("high_speed, packet", [(False, 64), (True, 512)])
def test_pyusb_parses_the_vendor_interface_and_its_bulk_endpoints(high_speed, packet) -> None:
    dev = found(EmulatedDevice(identity=Identity(high_speed=high_speed)),
                idVendor=0x1209, idProduct=0x0001)  # fmt: skip
    assert (dev.bcdUSB, dev.bNumConfigurations, dev.bus, dev.address) == (0x0200, 1, 1, 1)
    assert dev.speed == (usb.util.SPEED_HIGH if high_speed else usb.util.SPEED_FULL)
    cfg = dev[0]
    assert (cfg.bConfigurationValue, cfg.wTotalLength, cfg.bNumInterfaces) == (1, 32, 1)
    intf = cfg[(0, 0)]
    assert (intf.bInterfaceClass, intf.bInterfaceSubClass, intf.bInterfaceProtocol) == (
        0xFF, 0x48, p.PROTOCOL_VERSION,
    )  # fmt: skip
    eps = [(e.bEndpointAddress, usb.util.endpoint_type(e.bmAttributes), e.wMaxPacketSize)
           for e in intf]  # fmt: skip
    assert eps == [(0x01, usb.util.ENDPOINT_TYPE_BULK, packet), (0x81, 2, packet)]


def test_string_descriptors_come_back_through_get_descriptor() -> None:
    ident = Identity(manufacturer="Acme", product="Knob Ü", serial="SN-42")
    dev = found(EmulatedDevice(identity=ident))
    assert dev.langids == (0x0409,)
    assert (dev.manufacturer, dev.product, dev.serial_number) == ("Acme", "Knob Ü", "SN-42")


def test_find_matches_only_the_requested_ids() -> None:
    backend = EmulatedBackend(EmulatedDevice(), EmulatedDevice(identity=Identity(pid=0x0002)))
    assert len(list(usb.core.find(find_all=True, backend=backend))) == 2
    assert usb.core.find(backend=backend, idVendor=0x1209, idProduct=0x0003) is None
    second = usb.core.find(backend=backend, idProduct=0x0002)
    assert second.address == 2


def test_device_info_reads_back_through_the_driver() -> None:
    knob = UsbKnob(backend=EmulatedBackend(EmulatedDevice()))
    info = knob.info
    assert (info.kind, info.rate, info.max_output) == ("kinesthetic", 10_000.0, 0.18)
    assert info.resolution == pytest.approx(math.radians(0.001), rel=1e-6)
    assert info.firmware == "1.0.0"
    wire = knob.link.info
    assert (wire.buffer_capacity, wire.max_block, wire.report_samples) == (4096, 512, 100)
    assert (wire.watchdog_ms, wire.ramp_ms, wire.channels) == (50, 10, p.ALL_CHANNELS)


def test_a_device_reporting_a_lower_max_torque_is_read_as_such() -> None:
    emulated = EmulatedDevice(EmulatedKnob(KnobParams(max_torque=0.05)))
    assert UsbKnob(backend=EmulatedBackend(emulated)).info.max_output == 0.05


def test_a_vibrotactile_device_declares_the_drive_channel_only() -> None:
    knob = UsbKnob(backend=EmulatedBackend(EmulatedDevice(EmulatedKnob(vibrotactile=True))))
    assert (knob.info.kind, knob.info.max_output, knob.info.resolution) == ("vibrotactile", 1, 0)
    assert knob.link.info.channels == p.CH_D


def test_no_device_with_the_ids_is_one_sentence() -> None:
    knob = UsbKnob(pid=0x0007, backend=EmulatedBackend(EmulatedDevice()))
    with pytest.raises(DeviceNotFound, match=r"^no USB haptic device 1209:0007 found \(") as err:
        knob.open()
    assert str(err.value).count(".") == 0 and "\n" not in str(err.value)


def test_a_device_with_the_test_ids_but_another_interface_is_refused() -> None:
    other = EmulatedDevice()
    config = bytearray(other.config_bytes)
    config[9 + 5] = 0x03  # bInterfaceClass: HID
    other.config_bytes = bytes(config)
    assert UsbKnob.discover(backend=EmulatedBackend(other)) == []
    with pytest.raises(DeviceNotFound):
        UsbKnob(backend=EmulatedBackend(other)).open()


def test_discover_describes_each_device_found() -> None:
    old = EmulatedDevice(EmulatedKnob(declare_estimator=False))  # protocol 2.0
    backend = EmulatedBackend(
        EmulatedDevice(), EmulatedDevice(EmulatedKnob(vibrotactile=True)), old
    )
    assert UsbKnob.discover(backend=backend) == [
        "usb 1209:0001 on bus 1 address 1: Haptic knob (emulated), kinesthetic, 10000 Hz, "
        "max 180 mNm, 1-period delay, kalman",
        "usb 1209:0001 on bus 1 address 2: Haptic knob (emulated), vibrotactile, 10000 Hz, "
        "max 1 of full scale",
        "usb 1209:0001 on bus 1 address 3: Haptic knob (emulated), kinesthetic, 10000 Hz, "
        "max 180 mNm, 1-period delay, estimator not declared",
    ]


def configured(emulated: EmulatedDevice) -> usb.core.Device:
    dev = found(emulated)
    dev.set_configuration()
    return dev


def vendor_out(dev: usb.core.Device, request: int, value: int = 0, data: bytes | None = None):
    return dev.ctrl_transfer(p.REQUEST_TYPE_OUT, request, value, 0, data)


@pytest.mark.parametrize(
    "request_, value, data",
    [(0x7F, 0, None), (p.REQ_SET_LIMITS, 0, p.encode_limits(math.nan, 50)),
     (p.REQ_SET_LIMITS, 0, b"\x00" * 3), (p.REQ_START, 0, None), (p.REQ_START, 0x10, None)],
)  # fmt: skip
def test_invalid_control_requests_stall_endpoint_zero(request_, value, data) -> None:
    emulated = EmulatedDevice()
    dev = found(emulated)
    with pytest.raises(usb.core.USBError) as err:
        vendor_out(dev, request_, value, data)
    assert err.value.errno == errno.EPIPE
    assert emulated.knob.state == p.STATE_IDLE


def test_set_limits_lowers_the_torque_the_device_applies() -> None:
    """A constant drive of 0.1 N*m is applied as 0.04 after SET_LIMITS(0.04).

    The firmware applies each torque one period after it computes it: the first sample is 0.
    """
    emulated = EmulatedDevice()
    dev = configured(emulated)
    vendor_out(dev, p.REQ_SET_LIMITS, data=p.encode_limits(0.04, 50))
    vendor_out(dev, p.REQ_START, p.CH_D)
    dev.write(p.EP_OUT, p.encode_block(p.Block(0, p.CH_D, np.full((100, 1), 0.1), True)))
    report = p.decode_report(dev.read(p.EP_IN, p.report_bytes(100)))
    assert report.samples[:, 2].tolist() == [0.0] + [np.float32(0.04)] * 99
    assert report.flags == p.FLAG_SATURATED


def test_the_device_renders_a_non_finite_coefficient_as_zero_torque() -> None:
    """Defence in depth: a host that sends NaN gets zero torque for that sample and a flag.

    The firmware applies a torque one period after computing it: sample 40's zero lands at 41.
    """
    emulated = EmulatedDevice()
    dev = configured(emulated)
    vendor_out(dev, p.REQ_START, p.CH_D)
    d = np.full((100, 1), 0.02, dtype=np.float32)
    d[40] = np.nan
    dev.write(p.EP_OUT, p.encode_block(p.Block(0, p.CH_D, d, True)))
    report = p.decode_report(dev.read(p.EP_IN, p.report_bytes(100)))
    torque = report.samples[:, 2]
    assert torque[41] == 0.0 and torque[40] == np.float32(0.02) and np.isfinite(torque).all()
    assert report.flags & p.FLAG_NON_FINITE


def test_a_gap_in_sequence_numbers_and_a_garbled_block_are_flagged() -> None:
    emulated = EmulatedDevice()
    dev = configured(emulated)
    vendor_out(dev, p.REQ_START, p.CH_D)
    dev.write(p.EP_OUT, p.encode_block(p.Block(0, p.CH_D, np.zeros((50, 1)))))
    dev.write(p.EP_OUT, p.encode_block(p.Block(2, p.CH_D, np.zeros((50, 1)))))
    dev.write(p.EP_OUT, b"HB\x01\x01garbage")
    report = p.decode_report(dev.read(p.EP_IN, p.report_bytes(100)))
    assert report.flags & p.FLAG_SEQUENCE and report.flags & p.FLAG_BAD_BLOCK
    assert (report.last_block_seq, report.first_sample, len(report.samples)) == (2, 0, 100)
