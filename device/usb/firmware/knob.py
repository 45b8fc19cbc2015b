"""The device side of the USB protocol: the C firmware (ht_fw.c) run through ctypes.

`EmulatedKnob` is the firmware a knob would flash, compiled for the host (build.py): control
requests, block queue, safety, servo loop and telemetry reports are all C. Python keeps only the
motor and the hand (`MotorModel`: the `sim` knob's plant map over a period for the hand holding
it, device.sim.plant), which the host port's HAL (ports/sim/ht_sim.c) steps each period. It has
no clock of its own: time passes when the host reads a telemetry report (`send`: one report's
worth of samples) or when `advance()` is called (time passing with no host); the emulated
device's wall-clock mode (device.usb.emulated) calls `advance_samples` as the wall clock goes.
"""

from __future__ import annotations

import ctypes
from dataclasses import dataclass, field, replace
from functools import cache

import numpy as np

from device.sim import KnobParams
from device.sim.plant import held_plant, step_matrix
from device.usb import descriptors as desc
from device.usb import protocol as p
from device.usb.firmware.build import shared_library
from timeline.plugins.device_protocol import Hand

FIRMWARE_VERSION = (1, 0, 0)
_U8, _U16, _U32, _F64 = ctypes.c_uint8, ctypes.c_uint16, ctypes.c_uint32, ctypes.c_double
_MAP = _F64 * 10


class Config(ctypes.Structure):
    """ht_config of ht_fw.h (host build: ht_real is double)."""

    _fields_ = [  # noqa: RUF012 (ctypes' declaration)
        *((name, _U8) for name in ("kind", "channels", "delay", "protocol_minor", "estimator",
                                   "wait_first_block", "firmware_major", "firmware_minor")),
        ("firmware_patch", _U16), ("rate_hz", _U32), ("buffer_capacity", _U32),
        *((name, _U16) for name in ("max_block", "report_samples", "watchdog_ms", "ramp_ms")),
        *((name, _F64) for name in ("max_torque", "max_stiffness", "max_damping", "max_mass",
                                    "encoder_resolution", "inertia", "viscous", "coulomb",
                                    "velocity_cutoff", "acceleration_cutoff", "velocity_gain",
                                    "acceleration_gain")),
        ("gains", _F64 * 3),
    ]  # fmt: skip


class Table(ctypes.Structure):
    """ht_table of ht_fw.h: position tables (float32 here)."""

    _fields_ = [  # noqa: RUF012 (ctypes' declaration)
        ("count", _U32), ("start", _F64), ("rate", _F64),
        ("values", ctypes.POINTER(ctypes.c_float) * 3),
        ("counts", ctypes.POINTER(ctypes.c_int16) * 3), ("scales", _F64 * 3),
    ]  # fmt: skip


class HtIdentity(ctypes.Structure):
    """ht_identity of ht_fw.h: USB IDs, packet size and strings (UTF-8)."""

    _fields_ = [  # noqa: RUF012 (ctypes' declaration)
        ("vid", _U16), ("pid", _U16), ("packet_size", _U16), ("strings", ctypes.c_char_p * 3),
    ]  # fmt: skip


@cache
def library() -> ctypes.CDLL:
    """The compiled firmware with the host port (built once per source version)."""
    lib = ctypes.CDLL(str(shared_library()))
    pointer, size = ctypes.c_void_p, ctypes.c_size_t
    signatures = {
        "ht_fw_size": (size, []),
        "ht_sim_size": (size, []),
        "ht_fw_init": (ctypes.c_int, [pointer, ctypes.POINTER(Config), pointer]),
        "ht_sim_init": (None, [pointer, _MAP, _F64, _F64, _F64]),
        "ht_sim_set_hand": (None, [pointer, _MAP, _F64, _F64, _F64]),
        "ht_sim_set_trace": (None, [pointer, pointer, _U32]),
        "ht_sim_trace_len": (_U32, [pointer]),
        "ht_sim_run": (None, [pointer, _U32]),
        "ht_sim_status": (None, [pointer, _U32 * 11, _F64 * 2]),
        "ht_fw_control_in": (ctypes.c_int, [pointer, _U8, _U16, ctypes.c_char_p]),
        "ht_fw_control_out": (ctypes.c_int, [pointer, _U8, _U16, ctypes.c_char_p, _U16]),
        "ht_fw_bulk_out": (None, [pointer, ctypes.c_char_p, size]),
        "ht_fw_report": (size, [pointer, ctypes.c_char_p]),
        "ht_fw_play_table": (None, [pointer, ctypes.POINTER(Table), _F64]),
        "ht_fw_set_identity": (None, [pointer, ctypes.POINTER(HtIdentity)]),
        "ht_fw_descriptor": (ctypes.c_int, [pointer, _U8, _U8, ctypes.c_char_p, _U16]),
    }
    for name, (restype, argtypes) in signatures.items():
        function = getattr(lib, name)
        function.restype, function.argtypes = restype, argtypes
    return lib


@dataclass
class MotorModel:
    """The motor and the hand on it, as the `sim` knob models them: what the HAL steps."""

    params: KnobParams
    _maps: dict[tuple[float, float, float], tuple[float, ...]] = field(default_factory=dict)

    def rows(self, hand: Hand) -> tuple[float, ...]:
        """The plant's theta and omega rows over one period with this hand (as KnobPhysics)."""
        p = self.params
        key, a = held_plant(p.inertia, p.viscous, hand)
        if key not in self._maps:
            self._maps[key] = tuple(float(x) for x in step_matrix(a, p.period)[:2].ravel())
        return self._maps[key]


class EmulatedKnob:
    """A haptic device's firmware (the C one): control requests, block queue, safety, servo loop
    and telemetry reports, on the simulated motor and hand.

    `params` is the sim knob it drives (its max torque is the maximum GET_INFO declares; its
    watchdog ramp is the protocol's ramp). By default a knob has a one-period computation delay,
    as real firmware does (it computes on one sample and applies on the next), and declares it
    in GET_INFO. A vibrotactile device renders the drive term only, at +-1.0 of full scale, with
    no delay (it plays its samples open loop), and reports zero angle and velocity.
    A knob declares its estimator (protocol 2.1) and runs the float32 observer gains it
    declares; `declare_estimator=False` makes a protocol 2.0 device (58-byte GET_INFO).
    """

    def __init__(
        self,
        params: KnobParams | None = None,
        *,
        vibrotactile: bool = False,
        buffer_capacity: int = 4096,
        max_block: int = 512,
        report_samples: int = 100,
        watchdog_ms: int = 50,
        limits: tuple[float, float, float] = (100.0, 1.0, 1e-2),
        declare_estimator: bool = True,
    ) -> None:
        # A knob's firmware applies the torque it computed from one reading a period later; a
        # vibrotactile driver plays its samples open loop, with nothing to compute.
        params = params or KnobParams(
            max_torque=1.0 if vibrotactile else 0.18, delay=int(not vibrotactile)
        )
        estimator = _declared_estimator(params) if declare_estimator and not vibrotactile else {}
        if estimator and params.observer_gains is not None:
            # The firmware runs the float32 gains it declares, as a Cortex-M4F would hold them.
            params = replace(params, gains=estimator["observer_gains"])
        self.info = p.InfoPayload(
            kind=p.KIND_VIBROTACTILE if vibrotactile else p.KIND_KINESTHETIC,
            rate_hz=round(params.rate),
            max_torque=params.max_torque,
            max_stiffness=0.0 if vibrotactile else limits[0],
            max_damping=0.0 if vibrotactile else limits[1],
            max_mass=0.0 if vibrotactile else limits[2],
            encoder_resolution=0.0 if vibrotactile else params.quantum,
            buffer_capacity=buffer_capacity,
            max_block=max_block,
            report_samples=report_samples,
            channels=p.CH_D if vibrotactile else p.ALL_CHANNELS,
            watchdog_ms=watchdog_ms,
            ramp_ms=round(params.watchdog_ramp * 1000),
            inertia=0.0 if vibrotactile else params.inertia,
            viscous=0.0 if vibrotactile else params.viscous,
            coulomb=0.0 if vibrotactile else params.coulomb,
            delay=params.delay,
            firmware=FIRMWARE_VERSION,
            protocol_minor=p.PROTOCOL_MINOR if declare_estimator else 0,
            **estimator,
        )
        self.physics = MotorModel(params)
        self.hand = Hand("hold")
        self._lib = lib = library()
        self._fw = ctypes.create_string_buffer(lib.ht_fw_size())
        self._sim = ctypes.create_string_buffer(lib.ht_sim_size())
        self._status, self._reals = (_U32 * 11)(), (_F64 * 2)()
        self._out = ctypes.create_string_buffer(p.report_bytes(report_samples))
        self._trace: np.ndarray | None = None
        self._table: tuple[Table, list[np.ndarray]] | None = None
        self._identity: HtIdentity | None = None
        self._strings: ctypes.Array[ctypes.c_char_p] | None = None
        lib.ht_sim_init(
            self._sim, _MAP(*self.physics.rows(self.hand)), params.period, params.quantum,
            params.coulomb,
        )  # fmt: skip
        if lib.ht_fw_init(self._fw, ctypes.byref(_config(self.info, params)), self._sim):
            raise ValueError("the firmware refused its constants (buffer beyond HT_QUEUE_MAX?)")

    @property
    def vibrotactile(self) -> bool:
        return self.info.kind == p.KIND_VIBROTACTILE

    # --- the firmware's state, read from C ------------------------------------------------------
    def _read(self) -> tuple[list[int], list[float]]:
        self._lib.ht_sim_status(self._fw, self._status, self._reals)
        return list(self._status), list(self._reals)

    state = property(lambda self: self._read()[0][0], doc="idle, running or ramping")
    flags = property(lambda self: self._read()[0][1], doc="the latched fault flags")
    underruns = property(lambda self: self._read()[0][2], doc="samples played from an empty queue")
    overruns = property(lambda self: self._read()[0][3], doc="blocks dropped for lack of room")
    played = property(lambda self: self._read()[0][4], doc="samples since START")
    unreported = property(lambda self: self._read()[0][6], doc="samples played, not reported")
    mask = property(lambda self: self._read()[0][7], doc="the channel mask of the stream")
    last_block_seq = property(lambda self: self._read()[0][8], doc="the last block accepted")
    watchdog_ms = property(lambda self: self._read()[0][9], doc="the watchdog in force, ms")
    torque = property(lambda self: self._read()[1][0], doc="the last torque applied, N*m")
    torque_limit = property(lambda self: self._read()[1][1], doc="min(SET_LIMITS, max), N*m")

    @property
    def waiting(self) -> bool:
        """Started, and no sample queued or played yet: the stream begins with the first block."""
        status = self._read()[0]
        return status[0] == p.STATE_RUNNING and not status[4] and not status[5]

    # --- descriptors and control requests -------------------------------------------------------
    def set_identity(self, identity: desc.Identity) -> None:
        """Who the device says it is in its descriptors (the C keeps pointers to the strings)."""
        texts = (identity.manufacturer, identity.product, identity.serial)
        strings = (ctypes.c_char_p * 3)(*(text.encode() for text in texts))
        self._identity = HtIdentity(identity.vid, identity.pid, identity.packet_size, strings)
        self._strings = strings  # alive as long as the firmware points at them
        self._lib.ht_fw_set_identity(self._fw, ctypes.byref(self._identity))

    def descriptor(self, kind: int, index: int) -> bytes:
        """A standard descriptor's bytes, as the firmware answers GET_DESCRIPTOR; IndexError when
        it has none."""
        out = ctypes.create_string_buffer(255)
        n = self._lib.ht_fw_descriptor(self._fw, kind, index, out, 255)
        if n < 0:
            raise IndexError((kind, index))
        return out.raw[:n]

    def control_in(self, request: int, length: int) -> bytes:
        """Answer a vendor IN request, or raise ProtocolError (a STALL on endpoint 0)."""
        out = ctypes.create_string_buffer(p.INFO_SIZE)
        n = self._lib.ht_fw_control_in(self._fw, request, min(length, 0xFFFF), out)
        if n < 0:
            raise p.ProtocolError(f"unsupported IN request {request:#x} of {length} bytes")
        return out.raw[:n]

    def control_out(self, request: int, value: int, data: bytes) -> None:
        """Carry out a vendor OUT request, or raise ProtocolError (a STALL on endpoint 0)."""
        if request == p.REQ_START and not data:  # the hand holds the knob from START on
            rows = _MAP(*self.physics.rows(self.hand))
            hand = self.hand
            self._lib.ht_sim_set_hand(
                self._sim, rows, hand.push_torque, hand.push_ramp, hand.turn_speed
            )
        if self._lib.ht_fw_control_out(self._fw, request, value & 0xFFFF, data, len(data)) < 0:
            raise p.ProtocolError(f"the device refused OUT request {request:#x}")

    # --- bulk OUT and IN --------------------------------------------------------------------------
    def receive(self, data: bytes) -> None:
        """Take one OUT transfer: queue its samples, or count why it was dropped."""
        self._lib.ht_fw_bulk_out(self._fw, data, len(data))

    def send(self) -> bytes:
        """One IN transfer: play one report's worth of samples, then report the oldest ones."""
        self.advance_samples(self.info.report_samples)
        return self.report()

    def report(self) -> bytes:
        """The next telemetry report: up to one report's worth of the oldest unreported samples."""
        n = self._lib.ht_fw_report(self._fw, self._out)
        return self._out.raw[:n]

    # --- time -----------------------------------------------------------------------------------
    def advance(self, seconds: float) -> None:
        """Let time pass with no host: the queue plays, the watchdog watches."""
        self.advance_samples(round(seconds * self.info.rate_hz))

    def starve(self) -> None:
        """Let the queue run dry and one report period more, as if the host were that late."""
        self.advance_samples(self._read()[0][5] + self.info.report_samples)

    def advance_samples(self, n: int) -> None:
        """Play n servo periods."""
        if n > 0:
            self._lib.ht_sim_run(self._fw, n)

    # --- for tests: full precision, and position mode ----------------------------------------
    def record_trace(self, capacity: int) -> None:
        """Keep the next `capacity` periods' reading, velocity and torque in float64."""
        self._trace = np.zeros((capacity, 3))
        self._lib.ht_sim_set_trace(self._sim, self._trace.ctypes.data, capacity)

    @property
    def trace(self) -> np.ndarray:
        """The periods recorded since record_trace: rows of (angle, velocity, torque)."""
        if self._trace is None:
            return np.zeros((0, 3))
        return self._trace[: self._lib.ht_sim_trace_len(self._sim)]

    def play_table(
        self, tables: dict[str, np.ndarray], start: float, rate: float, origin: float = 0.0
    ) -> None:
        """Position mode: play float32 tables ("torque", "damping", "mass": values every 1/rate
        rad from `start`) at origin + the angle from now, with no host (ht_fw_play_table)."""
        hand = self.hand
        rows = _MAP(*self.physics.rows(hand))
        self._lib.ht_sim_set_hand(self._sim, rows, hand.push_torque, hand.push_ramp,
                                  hand.turn_speed)  # fmt: skip
        kept = [np.ascontiguousarray(tables[name], dtype=np.float32) if name in tables else None
                for name in ("torque", "damping", "mass")]  # fmt: skip
        table = Table(count=len(kept[0]), start=start, rate=rate)
        for i, values in enumerate(kept):
            if values is not None:
                table.values[i] = values.ctypes.data_as(ctypes.POINTER(ctypes.c_float))
        self._table = (table, kept)  # C holds pointers into these
        self._lib.ht_fw_play_table(self._fw, ctypes.byref(table), origin)


def _config(info: p.InfoPayload, params: KnobParams) -> Config:
    """The C firmware's constants: what GET_INFO declares, and the loop it runs (a 2.0 device
    declares no estimator but runs the sim's)."""
    declared = bool(info.protocol_minor)
    codes = {name: code for code, name in p.ESTIMATORS.items()}
    gains = params.observer_gains
    running = (0.0,) * 3 if gains is None else tuple(float(g) for g in gains)
    config = Config(
        kind=info.kind, channels=info.channels, delay=info.delay,
        protocol_minor=info.protocol_minor,
        estimator=info.estimator if declared else codes[params.estimator],
        firmware_major=info.firmware[0], firmware_minor=info.firmware[1],
        firmware_patch=info.firmware[2], rate_hz=info.rate_hz,
        buffer_capacity=info.buffer_capacity, max_block=info.max_block,
        report_samples=info.report_samples, watchdog_ms=info.watchdog_ms, ramp_ms=info.ramp_ms,
        max_torque=info.max_torque, max_stiffness=info.max_stiffness,
        max_damping=info.max_damping, max_mass=info.max_mass,
        encoder_resolution=info.encoder_resolution, inertia=info.inertia, viscous=info.viscous,
        coulomb=info.coulomb, velocity_cutoff=info.velocity_cutoff,
        acceleration_cutoff=info.acceleration_cutoff,
        velocity_gain=params.smoothing(params.velocity_cutoff),
        acceleration_gain=params.smoothing(params.acceleration_cutoff),
    )  # fmt: skip
    config.gains[:] = info.observer_gains if declared else running
    return config


def _declared_estimator(params: KnobParams) -> dict:
    """GET_INFO's estimator fields for a knob's params: cut-offs, and an observer's gains
    rounded to the float32 the wire (and the firmware) holds."""
    gains = params.observer_gains
    codes = {name: code for code, name in p.ESTIMATORS.items()}
    return {
        "estimator": codes[params.estimator],
        "velocity_cutoff": float(np.float32(params.velocity_cutoff)),
        "acceleration_cutoff": float(
            np.float32(params.acceleration_cutoff if gains is None else 0)
        ),
        "observer_gains": (0.0,) * 3 if gains is None else tuple(map(float, gains.astype("<f4"))),
    }
