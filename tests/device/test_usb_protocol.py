"""The USB wire protocol: exact byte layouts, round trips, and a decoder that never crashes."""

from __future__ import annotations

import struct
import zlib

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from device.usb import protocol as p

MASKS = st.integers(1, 15)


def test_a_block_has_the_documented_byte_layout() -> None:
    block = p.Block(seq=7, mask=p.CH_D | p.CH_B, samples=np.array([[0.5, -2.0]]), end=True)
    wire = p.encode_block(block)
    body = (
        b"HB" + bytes([2, 0b0101]) + (7).to_bytes(4, "little") + (1).to_bytes(2, "little")
        + (1).to_bytes(2, "little") + struct.pack("<ff", 0.5, -2.0)
    )  # fmt: skip
    assert wire == body + zlib.crc32(body).to_bytes(4, "little")
    assert len(wire) == p.block_bytes(1, block.mask) == 24


def test_a_report_has_the_documented_byte_layout() -> None:
    rows = np.array([[0.25, -1.5, 0.125]], dtype=np.float32)
    report = p.Report(3, p.STATE_RUNNING, 100, p.FLAG_SATURATED, 250, 0, 0, 9, rows)
    wire = p.encode_report(report)
    header = struct.pack("<2sBBIIHHIIII", b"HT", 2, 1, 3, 100, 1, 64, 250, 0, 0, 9)
    body = header + struct.pack("<fff", 0.25, -1.5, 0.125)
    assert wire == body + zlib.crc32(body).to_bytes(4, "little")
    assert p.decode_report(wire).samples.tolist() == rows.tolist()


def test_device_info_2_0_round_trips_in_58_bytes() -> None:
    info = p.InfoPayload(p.KIND_KINESTHETIC, 10_000, 0.25, 50.0, 0.5, 1e-3, 1e-5, 4096, 512,
                         100, p.ALL_CHANNELS, 50, 10, 1e-5, 1e-4, 1e-3, 1, (2, 3, 4),
                         protocol_minor=0)  # fmt: skip
    wire = p.encode_info(info)
    assert len(wire) == p.INFO_V20_SIZE == 58
    assert wire[41] == 1  # the delay sits in the byte version 2 first shipped as reserved 0
    back = p.decode_info(wire)
    assert back.rate_hz == 10_000 and back.firmware == (2, 3, 4) and back.report_samples == 100
    assert back.delay == 1
    assert back.max_torque == np.float32(0.25) and back.max_mass == np.float32(1e-3)
    assert (back.inertia, back.viscous, back.coulomb) == tuple(np.float32([1e-5, 1e-4, 1e-3]))


@pytest.mark.parametrize(
    "field, value, words",
    [(1, 3, "protocol version 3"), (6, 0, "non-positive"), (7, float("nan"), "non-finite"),
     (15, 0, "invalid channel mask"), (14, 0, "block, report or buffer"),
     (12, 100, "block, report or buffer"), (20, -1e-4, "non-finite rate or limit"),
     (16, 2, "2-period delay")],
)  # fmt: skip
def test_device_info_with_a_bad_field_is_refused(field: int, value: float, words: str) -> None:
    info = p.InfoPayload(p.KIND_KINESTHETIC, 10_000, 0.18, 50.0, 0.5, 1e-3, 1e-5, 4096, 512,
                         100, p.ALL_CHANNELS, 50, 10, protocol_minor=0)  # fmt: skip
    fields = list(p._INFO.unpack(p.encode_info(info)))
    fields[field] = value
    with pytest.raises(p.ProtocolError, match=words):
        p.decode_info(p._INFO.pack(*fields))


def test_limits_outside_the_documented_ranges_are_refused() -> None:
    assert p.decode_limits(p.encode_limits(0.1, 50)) == (pytest.approx(0.1), 50)
    for torque, watchdog in ((float("nan"), 50), (-1.0, 50), (0.1, 4), (0.1, 1001)):
        with pytest.raises(p.ProtocolError):
            p.decode_limits(p.encode_limits(torque, watchdog))


def test_block_lengths_never_fill_a_whole_number_of_packets() -> None:
    """Every block ends in a short packet (64-byte multiples would need a zero-length packet)."""
    for mask in range(1, 16):
        for wanted in range(1, 700):
            n = p.block_samples(wanted, mask, 512)
            assert min(wanted, 512) - 1 <= n <= min(wanted, 512)
            assert p.block_bytes(n, mask) % p.PACKET_FS != 0


def test_make_safe_zeroes_non_finite_samples_and_clamps_each_channel() -> None:
    rows = np.array([[0.3, 5.0], [np.nan, 1.0], [0.1, -np.inf], [-0.5, -0.5]])
    safe, zeroed, clamped = p.make_safe(rows, np.array([0.18, 2.0]))
    assert safe.tolist() == [[0.18, 2.0], [0.0, 0.0], [0.0, 0.0], [-0.18, -0.5]]
    assert (zeroed, clamped) == (2, 3)


finite32 = st.floats(width=32, allow_nan=False, allow_infinity=False)


@given(st.integers(0, 2**32 - 1), MASKS, st.data(), st.booleans())
def test_blocks_round_trip(seq: int, mask: int, data: st.DataObject, end: bool) -> None:
    n = data.draw(st.integers(0, 40))
    values = data.draw(st.lists(finite32, min_size=n * p.channel_count(mask),
                                max_size=n * p.channel_count(mask)))  # fmt: skip
    samples = np.array(values, dtype=np.float32).reshape(n, p.channel_count(mask))
    back = p.decode_block(p.encode_block(p.Block(seq, mask, samples, end)))
    assert (back.seq, back.mask, back.end) == (seq, mask, end)
    assert np.array_equal(back.samples, samples)


def _near_valid(magic: bytes, header_size: int) -> st.SearchStrategy[bytes]:
    """Bytes that start like a real message, so the decoder gets past its first checks."""
    return st.builds(
        lambda version, rest: magic + bytes([version]) + rest,
        st.sampled_from([p.PROTOCOL_VERSION] * 3 + [0, 1]),
        st.binary(min_size=header_size - 3, max_size=header_size + 80),
    )


def _mutated(valid: st.SearchStrategy[bytes]) -> st.SearchStrategy[bytes]:
    """A valid message with one byte changed, cut short, or extended."""

    def mutate(data: bytes, where: int, byte: int, how: int) -> bytes:
        where %= len(data)
        if how == 0:
            return data[:where] + bytes([byte]) + data[where + 1 :]
        return data[:where] if how == 1 else data + bytes([byte])

    return st.builds(mutate, valid, st.integers(0, 10**6), st.integers(0, 255), st.integers(0, 2))


VALID_BLOCKS = st.builds(
    lambda seq, mask, n, end: p.encode_block(
        p.Block(seq, mask, np.ones((n, p.channel_count(mask)), np.float32), end)
    ),
    st.integers(0, 2**32 - 1), MASKS, st.integers(0, 5), st.booleans(),
)  # fmt: skip


@settings(max_examples=400)
@given(
    st.one_of(
        st.binary(max_size=200), _near_valid(b"HB", p.BLOCK_HEADER_SIZE), _mutated(VALID_BLOCKS)
    )
)
def test_any_bytes_decode_to_a_block_or_a_protocol_error(data: bytes) -> None:
    try:
        block = p.decode_block(data)
    except p.ProtocolError as exc:
        assert str(exc)
        return
    assert len(data) == p.block_bytes(len(block.samples), block.mask)
    assert p.encode_block(block) == data


@settings(max_examples=400)
@given(st.one_of(st.binary(max_size=200), _near_valid(b"HT", p.REPORT_HEADER_SIZE)))
def test_any_bytes_decode_to_a_report_or_a_protocol_error(data: bytes) -> None:
    try:
        report = p.decode_report(data)
    except p.ProtocolError:
        return
    assert p.encode_report(report) == data


def test_every_single_bit_flip_is_refused_by_the_crc() -> None:
    rows = np.array([[0.1, -2.0, 0.05], [0.2, 3.0, -0.17], [0.0, 0.0, 0.0]], dtype=np.float32)
    report = p.encode_report(p.Report(5, p.STATE_RUNNING, 300, 0, 90, 0, 0, 4, rows))
    block = p.encode_block(p.Block(9, p.ALL_CHANNELS, rows[:, :1].repeat(4, axis=1), False))
    info = p.encode_info(
        p.InfoPayload(p.KIND_KINESTHETIC, 10_000, 0.18, 100.0, 1.0, 1e-2, 1e-5, 4096, 512, 100,
                      p.ALL_CHANNELS, 50, 10, 1e-5, 1e-4, 1e-3, 1, estimator=p.ESTIMATOR_KALMAN,
                      velocity_cutoff=2000.0, observer_gains=(0.3, 1900.0, 5.6e6))
    )  # fmt: skip
    flips = 0
    for wire, decode in ((report, p.decode_report), (block, p.decode_block), (info, p.decode_info)):
        for bit in range(8 * len(wire)):
            damaged = bytearray(wire)
            damaged[bit // 8] ^= 1 << (bit % 8)
            with pytest.raises(p.ProtocolError):
                decode(bytes(damaged))
            flips += 1
    assert flips == 8 * (len(report) + len(block) + len(info)) == 8 * (72 + 64 + 86)


@given(
    st.one_of(
        st.binary(max_size=90), _near_valid(b"HI", p.INFO_V20_SIZE), _near_valid(b"HI", p.INFO_SIZE)
    )
)
def test_any_bytes_decode_to_device_info_or_a_protocol_error(data: bytes) -> None:
    try:
        info = p.decode_info(data)
    except p.ProtocolError:
        return
    assert info.rate_hz > 0 and np.isfinite(info.max_torque) and info.max_torque > 0


@given(st.binary(max_size=16))
def test_any_bytes_decode_to_limits_or_a_protocol_error(data: bytes) -> None:
    try:
        torque, watchdog = p.decode_limits(data)
    except p.ProtocolError:
        return
    assert np.isfinite(torque) and 5 <= watchdog <= 1000
