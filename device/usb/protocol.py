"""The haptic-timeline USB wire protocol (docs/usb-protocol.md): encode and decode every message.

Both the host driver and the emulated device use this module, so the two cannot drift apart.
Everything on the wire is little-endian; coefficients and telemetry are IEEE-754 float32.
"""

from __future__ import annotations

import struct
import zlib
from dataclasses import dataclass

import numpy as np

from timeline.errors import HapticTimelineError
from timeline.plugins.device_protocol import Dynamics
from timeline.plugins.device_protocol.dynamics import OBSERVERS

PROTOCOL_VERSION = 2  # 2: blocks and reports end in a CRC-32 of their bytes
PROTOCOL_MINOR = 1  # 2.1: GET_INFO declares the estimator, sealed by a CRC-32 (2.0: 58 bytes)

# Default IDs: pid.codes' open-source VID with one of its *test* PIDs (1209:0001). A test ID is
# for development only; a product built to this protocol registers its own PID with pid.codes.
DEFAULT_VID = 0x1209
DEFAULT_PID = 0x0001

INTERFACE_CLASS = 0xFF  # vendor specific
INTERFACE_SUBCLASS = 0x48  # 'H'
INTERFACE_PROTOCOL = PROTOCOL_VERSION
INTERFACE_NUMBER = 0
EP_OUT = 0x01  # bulk OUT: coefficient blocks
EP_IN = 0x81  # bulk IN: telemetry reports
PACKET_FS = 64  # wMaxPacketSize of a bulk endpoint at full speed
PACKET_HS = 512  # ... and at high speed

# Vendor control requests (bmRequestType vendor | interface recipient, wIndex = interface number).
REQ_GET_INFO = 0x01  # IN, INFO_SIZE bytes
REQ_SET_LIMITS = 0x02  # OUT, LIMITS_SIZE bytes
REQ_START = 0x03  # OUT, no data; wValue = channel mask of the stream that follows
REQ_STOP = 0x04  # OUT, no data; ramp torque to zero and discard the queue
REQUEST_TYPE_IN = 0xC1  # device-to-host | vendor | interface
REQUEST_TYPE_OUT = 0x41  # host-to-device | vendor | interface

KIND_KINESTHETIC = 0
KIND_VIBROTACTILE = 1
KINDS = {KIND_KINESTHETIC: "kinesthetic", KIND_VIBROTACTILE: "vibrotactile"}

# Coefficient channels, in wire order. A block carries only the channels set in its mask.
CHANNELS = ("d", "k", "b", "m")
CH_D, CH_K, CH_B, CH_M = 1, 2, 4, 8
ALL_CHANNELS = CH_D | CH_K | CH_B | CH_M

# Telemetry fault and status flags (a report's `flags`).
FLAG_UNDERRUN = 1 << 0  # the queue ran empty while playing; latched until START
FLAG_OVERRUN = 1 << 1  # a block did not fit in the queue and was dropped; latched
FLAG_WATCHDOG = 1 << 2  # no block within the watchdog time: torque ramped to zero; latched
FLAG_SEQUENCE = 1 << 3  # a block's sequence number was not the next one; latched
FLAG_BAD_BLOCK = 1 << 4  # a block failed to decode and was dropped; latched
FLAG_NON_FINITE = 1 << 5  # a NaN/inf coefficient was replaced by zero torque; latched
FLAG_SATURATED = 1 << 6  # output was clamped to the torque limit during this report
FAULT_FLAGS = FLAG_UNDERRUN | FLAG_OVERRUN | FLAG_WATCHDOG | FLAG_SEQUENCE | FLAG_BAD_BLOCK
FLAG_NAMES = {
    FLAG_UNDERRUN: "underrun",
    FLAG_OVERRUN: "overrun",
    FLAG_WATCHDOG: "watchdog",
    FLAG_SEQUENCE: "sequence",
    FLAG_BAD_BLOCK: "bad block",
    FLAG_NON_FINITE: "non-finite",
    FLAG_SATURATED: "saturated",
}

# Device states (a report's `state`).
STATE_IDLE = 0  # not started, or stopped: zero torque
STATE_RUNNING = 1  # playing the queue
STATE_RAMPING = 2  # STOP, watchdog or end of stream: torque ramping to zero
STATES = {STATE_IDLE: "idle", STATE_RUNNING: "running", STATE_RAMPING: "ramping"}

BLOCK_FLAG_END = 1  # last block of the stream: play out the queue, then ramp to zero

_BLOCK_MAGIC = b"HB"
_REPORT_MAGIC = b"HT"
_INFO_MAGIC = b"HI"
_BLOCK_HEADER = struct.Struct("<2sBBIHH")  # magic, version, mask, seq, n, flags
_REPORT_HEADER = struct.Struct("<2sBBIIHHIIII")  # magic, version, state, seq, first, n, flags,
# fill, underruns, overruns, last block seq
_INFO = struct.Struct("<2sBBBBHIfffffIHHBBHHfff")  # version 2.0's answer
_ESTIMATOR = struct.Struct("<BBHfffff")  # 2.1: minor, estimator, reserved, cut-offs, L; + CRC
_CRC = struct.Struct("<I")  # trailer of blocks and reports
_LIMITS = struct.Struct("<fHH")  # max torque, watchdog ms, reserved
BLOCK_HEADER_SIZE = _BLOCK_HEADER.size
REPORT_HEADER_SIZE = _REPORT_HEADER.size
INFO_V20_SIZE = _INFO.size
INFO_SIZE = _INFO.size + _ESTIMATOR.size + 4  # what a 2.1 host asks for and a 2.1 device answers
LIMITS_SIZE = _LIMITS.size
WATCHDOG_RANGE_MS = (5, 1000)
MAX_DELAY = 1  # servo periods of computation delay GET_INFO may declare (the host models 0, 1)

# How the firmware estimates velocity and acceleration (GET_INFO byte 59, version 2.1).
ESTIMATOR_UNDECLARED = 0  # reserved: a 2.0 device, or one that does not say
ESTIMATOR_FILTER = 1  # backward differences through first-order low-passes at the cut-offs
ESTIMATOR_KALMAN = 2  # an observer with a steady-state Kalman gain L
ESTIMATOR_TRACKING = 3  # an observer with a pole-placing (tracking) gain L
ESTIMATORS = {ESTIMATOR_UNDECLARED: "", ESTIMATOR_FILTER: "filter", ESTIMATOR_KALMAN: "kalman",
              ESTIMATOR_TRACKING: "tracking"}  # fmt: skip


class ProtocolError(HapticTimelineError):
    """Bytes on the wire do not follow the haptic-timeline USB protocol."""


def channel_count(mask: int) -> int:
    """Number of coefficient channels a mask selects."""
    return bin(mask & ALL_CHANNELS).count("1")


def channel_names(mask: int) -> tuple[str, ...]:
    """Names of the channels a mask selects, in wire order."""
    return tuple(name for i, name in enumerate(CHANNELS) if mask & (1 << i))


def flag_names(flags: int) -> list[str]:
    """Human names of the flags set in a report."""
    return [name for bit, name in FLAG_NAMES.items() if flags & bit]


@dataclass(frozen=True)
class InfoPayload:
    """What GET_INFO answers: the device's kind, rate and limits."""

    kind: int
    rate_hz: int
    max_torque: float  # N*m (vibrotactile: 1.0 = full scale)
    max_stiffness: float  # N*m/rad
    max_damping: float  # N*m*s/rad
    max_mass: float  # kg*m^2
    encoder_resolution: float  # rad per count (0 for a vibrotactile device)
    buffer_capacity: int  # samples the queue holds
    max_block: int  # most samples in one OUT block
    report_samples: int  # samples in each IN telemetry report
    channels: int  # mask of the coefficients the device renders
    watchdog_ms: int
    ramp_ms: int
    inertia: float = 0.0  # kg*m^2 of the rotor and knob (0 when unknown)
    viscous: float = 0.0  # N*m*s/rad of the device's own damping
    coulomb: float = 0.0  # N*m of the device's own Coulomb friction
    delay: int = 0  # servo periods between reading the encoder and applying the torque from it
    firmware: tuple[int, int, int] = (1, 0, 0)
    protocol_version: int = PROTOCOL_VERSION
    estimator: int = ESTIMATOR_UNDECLARED  # version 2.1; a 2.0 answer leaves it undeclared
    velocity_cutoff: float = 0.0  # Hz, low-pass on the velocity difference (0 = none)
    acceleration_cutoff: float = 0.0  # Hz, low-pass on the acceleration difference (filter)
    observer_gains: tuple[float, float, float] = (0.0, 0.0, 0.0)  # L of an observer
    protocol_minor: int = PROTOCOL_MINOR  # 0: a 2.0 answer of 58 bytes

    def channel_limits(self, mask: int) -> np.ndarray:
        """Largest magnitude allowed for each channel in the mask, in wire order."""
        limits = (self.max_torque, self.max_stiffness, self.max_damping, self.max_mass)
        return np.array([limits[i] for i in range(4) if mask & (1 << i)], dtype=np.float64)

    def dynamics(self) -> Dynamics | None:
        """The rotor and servo loop declared, as the host's checks model them (None when the
        device does not declare its inertia; estimator "" when it does not declare that)."""
        if self.inertia <= 0:
            return None
        name = ESTIMATORS[self.estimator]
        gains = tuple(self.observer_gains) if name in OBSERVERS else ()
        return Dynamics(self.inertia, self.viscous, self.delay, self.velocity_cutoff,
                        self.acceleration_cutoff, gains, name)  # fmt: skip


def encode_info(info: InfoPayload) -> bytes:
    """Bytes of a GET_INFO answer: 58 for protocol 2.0, else sealed with the estimator."""
    major, minor, patch = info.firmware
    base = _INFO.pack(
        _INFO_MAGIC,
        info.protocol_version,
        info.kind,
        major,
        minor,
        patch,
        info.rate_hz,
        info.max_torque,
        info.max_stiffness,
        info.max_damping,
        info.max_mass,
        info.encoder_resolution,
        info.buffer_capacity,
        info.max_block,
        info.report_samples,
        info.channels,
        info.delay,
        info.watchdog_ms,
        info.ramp_ms,
        info.inertia,
        info.viscous,
        info.coulomb,
    )
    if not info.protocol_minor:
        return base
    extension = _ESTIMATOR.pack(
        info.protocol_minor,
        info.estimator,
        0,
        info.velocity_cutoff,
        info.acceleration_cutoff,
        *info.observer_gains,
    )
    return _sealed(base + extension)


def decode_info(data: bytes) -> InfoPayload:
    """Parse a GET_INFO answer (2.1, or 2.0's 58 bytes: estimator undeclared), or raise
    ProtocolError."""
    data = bytes(data)
    if len(data) not in (INFO_V20_SIZE, INFO_SIZE):
        raise ProtocolError(
            f"device info is {len(data)} bytes, expected {INFO_SIZE} (or {INFO_V20_SIZE})"
        )
    extension = (
        _decode_estimator(_unsealed(data, "device info"))
        if len(data) > INFO_V20_SIZE
        else {"protocol_minor": 0}
    )
    magic, version, kind, major, minor, patch, rate, *rest = _INFO.unpack_from(data)
    tmax, kmax, bmax, mmax, res, cap, max_block, report, channels, delay, watchdog, ramp = rest[:12]
    inertia, viscous, coulomb = rest[12:]
    if magic != _INFO_MAGIC:
        raise ProtocolError("device info does not start with the protocol's magic bytes")
    if version != PROTOCOL_VERSION:
        raise ProtocolError(
            f"device speaks protocol version {version}, this host speaks {PROTOCOL_VERSION}"
        )
    if kind not in KINDS:
        raise ProtocolError(f"device reports an unknown kind {kind}")
    limits = (tmax, kmax, bmax, mmax, res, inertia, viscous, coulomb)
    if not all(np.isfinite(x) and x >= 0 for x in limits) or tmax <= 0 or rate <= 0:
        raise ProtocolError("device info has a non-positive or non-finite rate or limit")
    if not channels & CH_D or channels & ~ALL_CHANNELS:
        raise ProtocolError(f"device info has an invalid channel mask {channels:#x}")
    if max_block <= 0 or report <= 0 or cap < max_block:
        raise ProtocolError("device info has an invalid block, report or buffer size")
    if delay > MAX_DELAY:
        raise ProtocolError(f"device info declares a {delay}-period delay, at most {MAX_DELAY}")
    if any(extension.get("observer_gains", ())):
        radius = observer_radius(extension["observer_gains"], 1.0 / rate)
        if not radius < 1.0:
            raise ProtocolError(
                f"device info declares an observer whose estimate diverges (its error map's "
                f"spectral radius is {radius:.4g}, not below 1)"
            )
    return InfoPayload(
        kind, rate, tmax, kmax, bmax, mmax, res, cap, max_block, report, channels, watchdog, ramp,
        inertia, viscous, coulomb, delay, (major, minor, patch), version, **extension,
    )  # fmt: skip


def observer_radius(gains: tuple[float, ...], period: float) -> float:
    """Spectral radius of an observer's error map (I - L C) A over a period (below 1: its
    estimate converges): A predicts angle, velocity and acceleration with the last held."""
    a = np.array([[1.0, period, period * period / 2.0], [0.0, 1.0, period], [0.0, 0.0, 1.0]])
    error = (np.eye(3) - np.outer(np.asarray(gains, dtype=np.float64), [1.0, 0.0, 0.0])) @ a
    with np.errstate(all="ignore"):
        radius = np.abs(np.linalg.eigvals(error)).max() if np.isfinite(error).all() else np.inf
    return float(radius)


def _decode_estimator(data: bytes) -> dict:
    """The fields 2.1 adds to GET_INFO (bytes 58 on, CRC already checked), or ProtocolError."""
    minor, code, reserved, vcut, acut, *gains = _ESTIMATOR.unpack_from(data, INFO_V20_SIZE)
    if minor < 1 or reserved:
        raise ProtocolError(f"device info has minor version {minor} or reserved bytes set")
    if code not in ESTIMATORS:
        raise ProtocolError(f"device info declares an unknown estimator {code}")
    if not all(np.isfinite(x) and x >= 0 for x in (vcut, acut)):
        raise ProtocolError("device info has a negative or non-finite estimator cut-off")
    observer = ESTIMATORS[code] in ("kalman", "tracking")
    if not all(np.isfinite(g) for g in gains) or observer != any(gains):
        raise ProtocolError(
            f"device info declares gains {gains} for its {ESTIMATORS[code] or 'undeclared'} "
            "estimator (an observer has finite gains, a filter none)"
        )
    return {"protocol_minor": minor, "estimator": code, "velocity_cutoff": vcut,
            "acceleration_cutoff": acut, "observer_gains": tuple(gains)}  # fmt: skip


def encode_limits(max_torque: float, watchdog_ms: int) -> bytes:
    """Bytes of a SET_LIMITS request."""
    return _LIMITS.pack(max_torque, watchdog_ms, 0)


def decode_limits(data: bytes) -> tuple[float, int]:
    """Parse a SET_LIMITS request into (max torque, watchdog ms), or raise ProtocolError."""
    data = bytes(data)
    if len(data) != LIMITS_SIZE:
        raise ProtocolError(f"limits are {len(data)} bytes, expected {LIMITS_SIZE}")
    max_torque, watchdog_ms, _ = _LIMITS.unpack(data)
    if not np.isfinite(max_torque) or max_torque < 0:
        raise ProtocolError("a torque limit must be a finite non-negative number")
    lo, hi = WATCHDOG_RANGE_MS
    if not lo <= watchdog_ms <= hi:
        raise ProtocolError(f"the watchdog must be {lo} to {hi} ms, not {watchdog_ms}")
    return float(max_torque), watchdog_ms


@dataclass(frozen=True)
class Block:
    """One OUT transfer: n samples of the channels in `mask`, as float32 of shape (n, channels)."""

    seq: int
    mask: int
    samples: np.ndarray
    end: bool = False


def _sealed(data: bytes) -> bytes:
    """data followed by its CRC-32 (zlib's, little-endian): the receiver sees any bit flip."""
    return data + _CRC.pack(zlib.crc32(data))


def _unsealed(data: bytes, what: str) -> bytes:
    """data without its CRC-32, or ProtocolError if the CRC does not match (damaged bytes)."""
    body, (crc,) = data[: -_CRC.size], _CRC.unpack_from(data, len(data) - _CRC.size)
    if zlib.crc32(body) != crc:
        raise ProtocolError(f"{what}'s CRC-32 does not match its bytes (damaged on the way)")
    return body


def encode_block(block: Block) -> bytes:
    """Bytes of one OUT transfer."""
    samples = np.ascontiguousarray(block.samples, dtype="<f4")
    if samples.ndim != 2 or samples.shape[1] != channel_count(block.mask):
        raise ValueError("block samples must have one column per channel in the mask")
    flags = BLOCK_FLAG_END if block.end else 0
    head = _BLOCK_HEADER.pack(
        _BLOCK_MAGIC, PROTOCOL_VERSION, block.mask, block.seq, len(samples), flags
    )
    return _sealed(head + samples.tobytes())


def decode_block(data: bytes) -> Block:
    """Parse one OUT transfer, or raise ProtocolError."""
    data = bytes(data)
    if len(data) < BLOCK_HEADER_SIZE + _CRC.size:
        raise ProtocolError(f"a block of {len(data)} bytes is shorter than its header")
    data = _unsealed(data, "a block")
    magic, version, mask, seq, n, flags = _BLOCK_HEADER.unpack_from(data)
    if magic != _BLOCK_MAGIC:
        raise ProtocolError("a block does not start with the protocol's magic bytes")
    if version != PROTOCOL_VERSION:
        raise ProtocolError(f"a block has protocol version {version}, expected {PROTOCOL_VERSION}")
    if mask == 0 or mask & ~ALL_CHANNELS:
        raise ProtocolError(f"a block has an invalid channel mask {mask:#x}")
    if flags & ~BLOCK_FLAG_END:
        raise ProtocolError(f"a block sets reserved flags {flags:#x}")
    width = channel_count(mask)
    if len(data) != BLOCK_HEADER_SIZE + 4 * width * n:
        raise ProtocolError(f"a block of {n} samples has {len(data)} bytes")
    samples = np.frombuffer(data, dtype="<f4", offset=BLOCK_HEADER_SIZE).reshape(n, width)
    return Block(seq, mask, samples, bool(flags & BLOCK_FLAG_END))


def block_bytes(n: int, mask: int) -> int:
    """Size in bytes of an OUT transfer carrying n samples."""
    return BLOCK_HEADER_SIZE + 4 * channel_count(mask) * n + _CRC.size


def block_samples(wanted: int, mask: int, max_block: int) -> int:
    """Samples for the next block: at most `wanted` and `max_block`, and never a transfer whose
    length is a multiple of 64 bytes, so every block ends in a short packet."""
    n = max(1, min(wanted, max_block))
    return n - 1 if block_bytes(n, mask) % PACKET_FS == 0 else n


@dataclass(frozen=True)
class Report:
    """One IN transfer: device status and per-sample telemetry (angle, velocity, torque)."""

    seq: int
    state: int
    first_sample: int  # index since START of the first sample reported
    flags: int
    buffer_fill: int  # samples queued after this report
    underruns: int  # samples played from an empty queue since START
    overruns: int  # blocks dropped for lack of room since START
    last_block_seq: int  # sequence number of the last block accepted
    samples: np.ndarray  # float32 (n, 3): angle rad, velocity rad/s, torque N*m


def encode_report(report: Report) -> bytes:
    """Bytes of one IN transfer."""
    samples = np.ascontiguousarray(report.samples, dtype="<f4").reshape(-1, 3)
    head = _REPORT_HEADER.pack(
        _REPORT_MAGIC,
        PROTOCOL_VERSION,
        report.state,
        report.seq,
        report.first_sample,
        len(samples),
        report.flags,
        report.buffer_fill,
        report.underruns,
        report.overruns,
        report.last_block_seq,
    )
    return _sealed(head + samples.tobytes())


def decode_report(data: bytes) -> Report:
    """Parse one IN transfer, or raise ProtocolError."""
    data = bytes(data)
    if len(data) < REPORT_HEADER_SIZE + _CRC.size:
        raise ProtocolError(f"a telemetry report of {len(data)} bytes is shorter than its header")
    data = _unsealed(data, "a telemetry report")
    (magic, version, state, seq, first, n, flags, fill, underruns, overruns, last_seq) = (
        _REPORT_HEADER.unpack_from(data)
    )
    if magic != _REPORT_MAGIC:
        raise ProtocolError("a telemetry report does not start with the protocol's magic bytes")
    if version != PROTOCOL_VERSION:
        raise ProtocolError(
            f"a telemetry report has protocol version {version}, expected {PROTOCOL_VERSION}"
        )
    if state not in STATES:
        raise ProtocolError(f"a telemetry report has an unknown state {state}")
    if len(data) != REPORT_HEADER_SIZE + 12 * n:
        raise ProtocolError(f"a telemetry report of {n} samples has {len(data)} bytes")
    samples = np.frombuffer(data, dtype="<f4", offset=REPORT_HEADER_SIZE).reshape(n, 3)
    return Report(seq, state, first, flags, fill, underruns, overruns, last_seq, samples)


def report_bytes(n: int) -> int:
    """Size in bytes of an IN transfer carrying n samples."""
    return REPORT_HEADER_SIZE + 12 * n + _CRC.size


def make_safe(samples: np.ndarray, limits: np.ndarray) -> tuple[np.ndarray, int, int]:
    """Clamp each channel to +-limit; zero every sample holding a NaN/inf.

    Returns (safe float64 samples, samples zeroed, values clamped). Host and device both apply it.
    """
    values = np.array(samples, dtype=np.float64, copy=True)
    bad = ~np.isfinite(values).all(axis=1)
    values[bad] = 0.0
    clipped = np.clip(values, -limits, limits)
    n_clamped = int(np.count_nonzero(clipped != values))
    return clipped, int(bad.sum()), n_clamped
