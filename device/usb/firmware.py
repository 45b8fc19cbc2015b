"""The device side of the USB protocol: what a knob's firmware does with requests and blocks.

`EmulatedKnob` keeps the queue, counters, flags, watchdog and ramp as docs/usb-protocol.md
states and renders every sample with the `sim` knob's physics (device.sim.KnobPhysics). It has
no clock of its own: time passes when the host reads a telemetry report (`send`: one report's
worth of samples) or when `advance()` is called (time passing with no host); the emulated
device's wall-clock mode (device.usb.emulated) calls `advance_samples` as the wall clock goes.
"""

from __future__ import annotations

import math
from collections import deque
from dataclasses import replace

import numpy as np

from device.sim import KnobParams, KnobPhysics
from device.usb import protocol as p
from timeline.plugins.device_protocol import CoefficientBlock, Hand, Telemetry

FIRMWARE_VERSION = (1, 0, 0)


class EmulatedKnob:
    """A haptic device's firmware: control requests, block queue, safety and telemetry reports.

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
        # The sim's own watchdog starts at once: this firmware calls run_idle only to ramp down.
        self._params = replace(params, watchdog_timeout=0.0)
        self.physics = KnobPhysics(self._params)
        self.hand = Hand("hold")
        self.torque_limit = params.max_torque
        self.watchdog_ms = watchdog_ms
        self.state = p.STATE_IDLE
        self.mask = 0
        self.flags = 0
        self.underruns = 0
        self.overruns = 0
        self.played = 0  # samples since START
        self.last_block_seq = 0
        self.torque = 0.0  # the last torque applied, N*m
        self._queue: deque[np.ndarray] = deque()
        self._queued = 0
        self._expected_seq = 0
        self._end = False
        self._since_block = 0
        self._ramp_left = 0
        self._hold = np.zeros((1, 4))
        self._report_seq = 0
        self._saturated = False
        self._unreported: deque[np.ndarray] = deque()

    @property
    def vibrotactile(self) -> bool:
        return self.info.kind == p.KIND_VIBROTACTILE

    # --- control requests -------------------------------------------------------------------
    def control_in(self, request: int, length: int) -> bytes:
        """Answer a vendor IN request, or raise ProtocolError (a STALL on endpoint 0)."""
        if request == p.REQ_GET_INFO and length >= p.INFO_V20_SIZE:
            return p.encode_info(self.info)[:length]  # a 2.0 host asks for 58 bytes: the 2.0 part
        raise p.ProtocolError(f"unsupported IN request {request:#x} of {length} bytes")

    def control_out(self, request: int, value: int, data: bytes) -> None:
        """Carry out a vendor OUT request, or raise ProtocolError (a STALL on endpoint 0)."""
        if request == p.REQ_SET_LIMITS:
            limit, watchdog = p.decode_limits(data)
            self.torque_limit = min(limit, self.info.max_torque)
            self.watchdog_ms = watchdog
        elif request == p.REQ_START and not data:
            if not value or value & ~self.info.channels:
                raise p.ProtocolError(f"the device cannot render channel mask {value:#x}")
            self._start(value)
        elif request == p.REQ_STOP and not data:
            self._clear_queue()
            self._end = True
            if self.state == p.STATE_RUNNING:
                self._begin_ramp()
        else:
            raise p.ProtocolError(f"unsupported OUT request {request:#x}")

    def _start(self, mask: int) -> None:
        self._clear_queue()
        self.physics.params = replace(self._params, max_torque=self.torque_limit)
        self.physics.start(self.hand)
        self.state = p.STATE_RUNNING
        self.mask = mask
        self.flags = self.underruns = self.overruns = self.played = 0
        self.last_block_seq = self._expected_seq = self._since_block = 0
        self._end = False
        self._hold = np.zeros((1, 4))
        self._unreported.clear()

    def _clear_queue(self) -> None:
        self._queue.clear()
        self._queued = 0

    # --- bulk OUT -------------------------------------------------------------------------------
    def receive(self, data: bytes) -> None:
        """Take one OUT transfer: queue its samples, or count why it was dropped."""
        if self.state != p.STATE_RUNNING or self._end:
            return  # blocks outside a stream are ignored
        try:
            block = p.decode_block(data)
        except p.ProtocolError:
            self.flags |= p.FLAG_BAD_BLOCK
            return
        if block.mask & ~self.mask:
            self.flags |= p.FLAG_BAD_BLOCK
            return
        if block.seq != self._expected_seq:
            self.flags |= p.FLAG_SEQUENCE
        self._expected_seq = block.seq + 1
        if self._queued + len(block.samples) > self.info.buffer_capacity:
            self.overruns += 1
            self.flags |= p.FLAG_OVERRUN
            return
        safe, zeroed, _ = p.make_safe(block.samples, self.info.channel_limits(block.mask))
        if zeroed:
            self.flags |= p.FLAG_NON_FINITE
        full = np.zeros((len(safe), 4))
        full[:, [i for i in range(4) if block.mask & (1 << i)]] = safe
        if len(full):
            self._queue.append(full)
            self._queued += len(full)
        self.last_block_seq = block.seq
        self._since_block = 0
        self._end = block.end

    # --- bulk IN --------------------------------------------------------------------------------
    def send(self) -> bytes:
        """One IN transfer: play one report's worth of samples, then report the oldest ones."""
        self.advance_samples(self.info.report_samples)
        return self.report()

    @property
    def unreported(self) -> int:
        """Samples played and not reported yet."""
        return sum(map(len, self._unreported))

    @property
    def waiting(self) -> bool:
        """Started, and no sample queued or played yet: the stream begins with the first block."""
        return self.state == p.STATE_RUNNING and not self.played and not self._queued

    def report(self) -> bytes:
        """The next telemetry report: up to one report's worth of the oldest unreported samples."""
        rows = np.concatenate(self._unreported) if self._unreported else np.zeros((0, 3))
        n = min(self.info.report_samples, len(rows))
        self._unreported.clear()
        if len(rows) > n:
            self._unreported.append(rows[n:])
        report = p.Report(
            self._report_seq,
            self.state,
            self.played - len(rows),
            self.flags | (p.FLAG_SATURATED if self._saturated else 0),
            self._queued,
            self.underruns,
            self.overruns,
            self.last_block_seq,
            rows[:n],
        )
        self._report_seq += 1
        self._saturated = False
        return p.encode_report(report)

    # --- time -----------------------------------------------------------------------------------
    def advance(self, seconds: float) -> None:
        """Let time pass with no host: the queue plays, the watchdog watches."""
        self.advance_samples(round(seconds * self.info.rate_hz))

    def starve(self) -> None:
        """Let the queue run dry and one report period more, as if the host were that late."""
        self.advance_samples(self._queued + self.info.report_samples)

    def advance_samples(self, n: int) -> None:
        """Play n servo periods."""
        while n > 0:
            n -= self._play_chunk(n)

    def _play_chunk(self, n: int) -> int:
        """Play up to n samples without a change of state; returns how many were played."""
        if self.state == p.STATE_RUNNING:
            watchdog_left = self._watchdog_samples() - self._since_block
            if not self._end and watchdog_left <= 0:
                self.flags |= p.FLAG_WATCHDOG
                self._begin_ramp()
            elif self._end and not self._queued:
                self._begin_ramp()
            else:
                m = n if self._end else min(n, watchdog_left)
                coeffs = self._take(m) if self._queued else self._underrun(m)
                self._since_block += len(coeffs)
                return self._record(self.physics.run_block(self._block(coeffs)))
        if self.state == p.STATE_RAMPING:
            n = min(n, self._ramp_left)
            self._ramp_left -= n
            if not self._ramp_left:
                self.state = p.STATE_IDLE
        return self._record(self.physics.run_idle(n))

    def _watchdog_samples(self) -> int:
        return max(1, round(self.watchdog_ms * self.info.rate_hz / 1000))

    def _take(self, n: int) -> np.ndarray:
        head = self._queue[0]
        coeffs = head[:n]
        if len(head) > n:
            self._queue[0] = head[n:]
        else:
            self._queue.popleft()
        self._queued -= len(coeffs)
        self._hold = coeffs[-1:]
        return coeffs

    def _underrun(self, n: int) -> np.ndarray:
        """Keep rendering the last sample's coefficients while the queue is empty."""
        self.underruns += n
        self.flags |= p.FLAG_UNDERRUN
        return np.repeat(self._hold, n, axis=0)

    def _block(self, coeffs: np.ndarray) -> CoefficientBlock:
        d, k, b, m = coeffs.T
        return CoefficientBlock(d, k, b, m if self.mask & p.CH_M else None)

    def _begin_ramp(self) -> None:
        """Scale the torque law down to zero over the ramp time (the sim's run_idle)."""
        self.state = p.STATE_RAMPING
        # + 1 for the sample where the ramp reaches zero, + delay for that zero to be applied
        ramp = max(1, math.ceil(self.info.ramp_ms * self.info.rate_hz / 1000))
        self._ramp_left = ramp + 1 + self.info.delay

    def _record(self, tel: Telemetry) -> int:
        n = len(tel)
        if n:
            self._saturated |= bool(tel.saturated.any())
            self.torque = float(tel.torque[-1])
            self.played += n
            if self.vibrotactile:
                rows = np.column_stack([np.zeros(n), np.zeros(n), tel.torque])
            else:
                rows = np.column_stack([tel.angle, tel.velocity, tel.torque])
            self._unreported.append(rows)
        return n


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
