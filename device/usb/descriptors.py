"""Standard USB descriptors of a haptic-timeline device, as the bytes its firmware would send.

The emulated backend parses these bytes into the attribute objects pyusb expects, as libusb does
for real hardware, so the descriptors have one source.
"""

from __future__ import annotations

import struct
from dataclasses import dataclass
from types import SimpleNamespace

import usb.util

from device.usb import protocol

DESC_DEVICE = 1
DESC_CONFIGURATION = 2
DESC_STRING = 3
DESC_INTERFACE = 4
DESC_ENDPOINT = 5
LANGID_EN_US = 0x0409
_DEVICE = struct.Struct("<BBHBBBBHHHBBBB")
_CONFIG = struct.Struct("<BBHBBBBB")
_INTERFACE = struct.Struct("<BBBBBBBBB")
_ENDPOINT = struct.Struct("<BBBBHB")


@dataclass(frozen=True)
class Identity:
    """Who the device says it is."""

    vid: int = protocol.DEFAULT_VID
    pid: int = protocol.DEFAULT_PID
    manufacturer: str = "haptic-timeline"
    product: str = "Haptic knob (emulated)"
    serial: str = "EMU-0001"
    high_speed: bool = False

    @property
    def packet_size(self) -> int:
        return protocol.PACKET_HS if self.high_speed else protocol.PACKET_FS


def device_descriptor(ident: Identity) -> bytes:
    """The 18-byte device descriptor."""
    return _DEVICE.pack(
        _DEVICE.size, DESC_DEVICE, 0x0200, 0, 0, 0, 64, ident.vid, ident.pid, 0x0100, 1, 2, 3, 1
    )


def configuration_descriptor(ident: Identity) -> bytes:
    """The whole configuration descriptor: one vendor interface with two bulk endpoints."""
    endpoints = b"".join(
        _ENDPOINT.pack(
            _ENDPOINT.size,
            DESC_ENDPOINT,
            address,
            usb.util.ENDPOINT_TYPE_BULK,
            ident.packet_size,
            0,
        )
        for address in (protocol.EP_OUT, protocol.EP_IN)
    )
    interface = _INTERFACE.pack(
        _INTERFACE.size,
        DESC_INTERFACE,
        protocol.INTERFACE_NUMBER,
        0,
        2,
        protocol.INTERFACE_CLASS,
        protocol.INTERFACE_SUBCLASS,
        protocol.INTERFACE_PROTOCOL,
        0,
    )
    total = _CONFIG.size + len(interface) + len(endpoints)
    # bmAttributes 0xC0: self-powered (the motor has its own supply); bMaxPower 50 = 100 mA.
    config = _CONFIG.pack(_CONFIG.size, DESC_CONFIGURATION, total, 1, 1, 0, 0xC0, 50)
    return config + interface + endpoints


def string_descriptor(ident: Identity, index: int) -> bytes:
    """String descriptor `index` (0: the LANGID list); IndexError when there is none."""
    if index == 0:
        return struct.pack("<BBH", 4, DESC_STRING, LANGID_EN_US)
    text = (ident.manufacturer, ident.product, ident.serial)[index - 1] if index <= 3 else None
    if text is None:
        raise IndexError(index)
    body = text.encode("utf-16-le")
    return bytes([2 + len(body), DESC_STRING]) + body


def _parse(layout: struct.Struct, data: bytes, names: str, **extra: object) -> SimpleNamespace:
    values = layout.unpack_from(data)
    return SimpleNamespace(**dict(zip(names.split(), values, strict=True)), **extra)


def parse_device(data: bytes, address: int, bus: int, high_speed: bool) -> SimpleNamespace:
    """The device descriptor object pyusb copies from (with bus, address, port and speed)."""
    return _parse(
        _DEVICE,
        data,
        "bLength bDescriptorType bcdUSB bDeviceClass bDeviceSubClass bDeviceProtocol "
        "bMaxPacketSize0 idVendor idProduct bcdDevice iManufacturer iProduct iSerialNumber "
        "bNumConfigurations",
        address=address,
        bus=bus,
        port_number=1,
        port_numbers=(1,),
        speed=usb.util.SPEED_HIGH if high_speed else usb.util.SPEED_FULL,
    )


def parse_configuration(data: bytes) -> SimpleNamespace:
    """The configuration descriptor object."""
    return _parse(
        _CONFIG,
        data,
        "bLength bDescriptorType wTotalLength bNumInterfaces bConfigurationValue iConfiguration "
        "bmAttributes bMaxPower",
        extra_descriptors=[],
    )


def parse_interface(data: bytes) -> SimpleNamespace:
    """The interface descriptor object (from the bytes after the configuration descriptor)."""
    return _parse(
        _INTERFACE,
        data[_CONFIG.size :],
        "bLength bDescriptorType bInterfaceNumber bAlternateSetting bNumEndpoints "
        "bInterfaceClass bInterfaceSubClass bInterfaceProtocol iInterface",
        extra_descriptors=[],
    )


def parse_endpoint(data: bytes, index: int) -> SimpleNamespace:
    """Endpoint descriptor `index` of the interface; IndexError past the last one."""
    offset = _CONFIG.size + _INTERFACE.size + index * _ENDPOINT.size
    if not 0 <= index < 2:
        raise IndexError(index)
    return _parse(
        _ENDPOINT,
        data[offset:],
        "bLength bDescriptorType bEndpointAddress bmAttributes wMaxPacketSize bInterval",
        bRefresh=0,
        bSynchAddress=0,
        extra_descriptors=[],
    )
