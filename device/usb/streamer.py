"""Streaming a program to an open device: re-blocking, safety, pacing and telemetry.

The host keeps the device's queue at most `lead` samples ahead of what it has played, as the
device reports it (docs/usb-protocol.md, section 4), and checks every telemetry report. It
counts the blocks it writes later than the lead on the wall clock (the device plays from the
first block on, one sample per period): each would have reached a real knob after its queue ran
dry.
"""

from __future__ import annotations

import time
from collections import deque
from collections.abc import Iterable, Iterator

import numpy as np

from device.sim.stability import stability_flags
from device.usb import protocol as p
from device.usb.errors import DeviceFault, DeviceUnderrun, UsbDeviceError
from device.usb.link import Link
from timeline.limits.servo import hand_loads
from timeline.plugins.device_protocol import (
    CoefficientBlock,
    LatenessMeter,
    LiveTelemetry,
    Monitor,
    Progress,
    Telemetry,
)


class Chunker:
    """Cuts a stream of CoefficientBlocks into (n, channels) arrays, knowing which is last."""

    def __init__(self, blocks: Iterable[CoefficientBlock], names: tuple[str, ...]) -> None:
        self._blocks: Iterator[CoefficientBlock] = iter(blocks)
        self._names = names
        self._parts: deque[np.ndarray] = deque()
        self._have = 0
        self._done = False
        self.dropped: set[str] = set()  # layers with values that the stream does not carry

    def _pull(self) -> None:
        block = next(self._blocks, None)
        if block is None:
            self._done = True
            return
        for name in ("k", "b", "m"):
            values = getattr(block, name)
            if name not in self._names and values is not None and np.any(values):
                self.dropped.add(name)
        columns = [getattr(block, name) for name in self._names]
        n = len(block)
        rows = np.column_stack([np.zeros(n) if c is None else c for c in columns])
        if n:
            self._parts.append(rows)
            self._have += n

    def available(self, n: int) -> int:
        """How many of the next n samples exist (reading ahead one sample to spot the end)."""
        while self._have <= n and not self._done:
            self._pull()
        return min(n, self._have)

    def take(self, n: int) -> tuple[np.ndarray, bool]:
        """Up to n samples, and whether they are the stream's last."""
        self.available(n)
        out: list[np.ndarray] = []
        need = n
        while need and self._parts:
            head = self._parts.popleft()
            out.append(head[:need])
            if len(head) > need:
                self._parts.appendleft(head[need:])
            need -= len(out[-1])
        self._have -= n - need
        rows = np.concatenate(out) if out else np.zeros((0, len(self._names)))
        return rows, self._done and not self._have


TORQUE_TOLERANCE = 1e-6  # relative: the float32 limit itself is a valid report
MAX_REPORTED_SPEED = 1e6  # rad/s: beyond this a report is corrupt, not a knob turning


def _sizes(info: p.InfoPayload, lead_s: float, block_s: float) -> tuple[int, int]:
    """Samples per block (at most the device's largest) and the lead: at least two blocks, at
    most the buffer's capacity."""
    block_n = max(1, min(round(block_s * info.rate_hz), info.max_block))
    lead = max(round(lead_s * info.rate_hz), 2 * block_n)
    return block_n, min(lead, info.buffer_capacity)


class Stream:
    """One play: START, blocks paced by telemetry, END, and the telemetry it gathered."""

    def __init__(
        self,
        link: Link,
        mask: int,
        torque_limit: float,
        lead_s: float,
        block_s: float,
        start_block_s: float | None = None,
    ) -> None:
        """`start_block_s`: the blocks that fill the lead at START go out this long (at most the
        device's largest block; default `block_s`): fewer transfers, so a host descheduled in
        the middle of them finds more queued."""
        info = link.info
        self.link = link
        self.mask = mask
        self.rate = info.rate_hz
        self.limits = info.channel_limits(mask)
        self.limits[0] = np.float32(min(torque_limit, info.max_torque))
        self.block_n, self.lead_n = _sizes(info, lead_s, block_s)
        start = block_s if start_block_s is None else start_block_s
        self.start_n = max(self.block_n, _sizes(info, lead_s, start)[0])
        if self.lead_n - self.block_n < info.report_samples:
            raise UsbDeviceError(
                f"the USB haptic device's buffer ({info.buffer_capacity} samples) cannot hold a "
                f"telemetry report ({info.report_samples}) plus a block ({self.block_n})"
            )
        self.zeroed = 0
        self.clamped = 0
        self.underruns = 0  # samples the device played from an empty queue, as last reported
        self.lateness = LatenessMeter(self.lead_n / self.rate)
        self._first_write: float | None = None  # perf_counter of the first block written
        self._sent: list[np.ndarray] = []
        self._received: list[np.ndarray] = []
        self._n_sent = 0
        self._n_received = 0

    @staticmethod
    def lead_seconds(info: p.InfoPayload, lead_s: float, block_s: float) -> float:
        """The lead a stream to this device keeps (s): the one asked for, within its buffer."""
        return _sizes(info, lead_s, block_s)[1] / info.rate_hz

    def run(
        self,
        chunker: Chunker,
        progress: Progress | None = None,
        total: float | None = None,
        monitor: Monitor | None = None,
    ) -> None:
        """Stream everything the chunker yields and read telemetry until all of it is played."""
        if not chunker.available(self.lead_n):
            return  # an empty program: nothing to play
        # The lead is read ahead: the device plays from the first block on, so the blocks that
        # fill its queue go out back to back, not one per pull from a live stream.
        seq, fill, since, end = 0, 0, 0, False
        self.link.start(self.mask)
        while not end or self._n_received < self._n_sent:
            while not end and fill + since + self.block_n <= self.lead_n:
                size = self.block_n if self._n_received else self.start_n  # filling the lead
                size = max(self.block_n, min(size, self.lead_n - fill - since))
                n = p.block_samples(chunker.available(size), self.mask, size)
                rows, end = chunker.take(n)
                self._count_lateness()
                self.link.write_block(p.Block(seq, self.mask, self._safe(rows), end))
                seq += 1
                since += len(rows)
            report = self.link.read_report()
            first = self._n_received
            self._check(report, end)
            if monitor and len(report.samples):
                rows = report.samples.astype(np.float64)
                time = (first + np.arange(len(rows))) / self.rate
                monitor(LiveTelemetry(time, rows[:, 0], rows[:, 2]))
            fill, since = report.buffer_fill, 0
            if progress:
                progress(min(self._n_received, self._n_sent) / self.rate, total)

    def _count_lateness(self) -> None:
        """The block about to go out plays from sample _n_sent, one period each from the first."""
        now = time.perf_counter()
        if self._first_write is None:
            self._first_write = now
        self.lateness.handed(self._first_write + self._n_sent / self.rate, now)

    def _safe(self, rows: np.ndarray) -> np.ndarray:
        safe, zeroed, clamped = p.make_safe(rows, self.limits)
        self.zeroed += zeroed
        self.clamped += clamped
        wire = safe.astype(np.float32)
        self._sent.append(wire)
        self._n_sent += len(wire)
        return wire

    def _check(self, report: p.Report, end: bool) -> None:
        if report.first_sample != self._n_received:
            raise UsbDeviceError(
                f"the USB haptic device's telemetry jumped from sample {self._n_received} "
                f"to {report.first_sample}"
            )
        self.underruns = report.underruns
        self._check_samples(report.samples)
        self._received.append(report.samples)
        self._n_received += len(report.samples)
        at = f"{self._n_received / self.rate:.3f} s"
        if report.flags & p.FLAG_UNDERRUN or report.underruns:
            raise DeviceUnderrun(
                f"the USB haptic device ran out of samples at {at} ({report.underruns} samples "
                "played from an empty queue) because the host fell behind, so playback stopped"
            )
        if report.flags & p.FLAG_WATCHDOG:
            raise DeviceFault(
                f"the USB haptic device's watchdog ramped the torque to zero at {at} because no "
                "block arrived in time"
            )
        faults = report.flags & (p.FAULT_FLAGS | p.FLAG_NON_FINITE)  # NaN reached the device
        if faults or report.overruns:
            names = ", ".join(p.flag_names(faults | (p.FLAG_OVERRUN if report.overruns else 0)))
            raise DeviceFault(f"the USB haptic device reported {names} at {at}; playback stopped")
        if report.state == p.STATE_IDLE and not end:
            raise DeviceFault(f"the USB haptic device stopped by itself at {at}")

    def _check_samples(self, rows: np.ndarray) -> None:
        """Refuse telemetry that cannot be true: NaN/inf, or torque beyond the limit it was sent.

        The device clamps every sample to the limit it was given, so a larger torque means the
        report is corrupt or the device broke its promise; either way playback stops (STOP).
        """
        if not len(rows):
            return
        bad = ~np.isfinite(rows).all(axis=1)
        torque_limit = float(self.limits[0]) * (1 + TORQUE_TOLERANCE)
        bad |= np.abs(rows[:, 2].astype(np.float64)) > torque_limit
        bad |= np.abs(rows[:, 1].astype(np.float64)) > MAX_REPORTED_SPEED
        if not bad.any():
            return
        i = int(np.argmax(bad))
        angle, speed, torque = (float(x) for x in rows[i])
        raise DeviceFault(
            f"the USB haptic device reported an impossible sample at "
            f"{(self._n_received + i) / self.rate:.4f} s (angle {angle:g} rad, speed "
            f"{speed:g} rad/s, torque {torque:g} N*m; limit {float(self.limits[0]):g} N*m), "
            "so playback stopped"
        )

    def telemetry(self, judged: bool = True) -> Telemetry:
        """What the device reported for the samples sent, with the layers as sent, and (if
        `judged`) the stability flags of the whole play (about 0.3 s per played second at
        20,000 clips: every hand's loop at each change of the layers)."""
        n = self._n_sent
        rows = np.concatenate(self._received)[:n] if self._received else np.zeros((0, 3))
        sent = np.concatenate(self._sent) if self._sent else np.zeros((0, len(self.limits)))
        if len(rows) < n:
            raise UsbDeviceError(f"the USB haptic device reported {len(rows)} of {n} samples")
        angle, velocity, torque = (rows[:, i].astype(np.float64) for i in range(3))
        layers = {
            name: sent[:, i].astype(np.float64) for i, name in enumerate(p.channel_names(self.mask))
        }
        time = np.arange(n) * (1.0 / self.rate)
        saturated = np.abs(torque) >= self.limits[0]
        energy = self._energy(angle, torque)
        flags = self._flags(time, layers) if judged else ()
        return Telemetry(float(self.rate), time, angle, velocity, torque, energy, saturated,
                         layers, flags, tuple(self.warnings()))  # fmt: skip

    def _energy(self, angle: np.ndarray, torque: np.ndarray) -> np.ndarray:
        """Energy the device put in (J), as the sim counts it, estimated from the encoder.

        Motor work (torque held over each period times the encoder's step) minus what the
        device's own viscous and Coulomb friction (from GET_INFO) dissipated over that step.
        """
        info = self.link.info
        step = np.diff(angle, append=angle[-1:])
        lost = info.viscous * step * step * self.rate + info.coulomb * np.abs(step)
        return np.cumsum(torque * step - lost)

    def _flags(self, time: np.ndarray, layers: dict[str, np.ndarray]) -> tuple:
        """The sim's stability rules applied to the coefficients sent (kinesthetic devices), the
        whole loop judged with every hand the docs offer, as `check` judges it."""
        dynamics = self.link.info.dynamics()
        if "k" not in layers or dynamics is None:
            return ()
        k, b, m = layers["k"], layers["b"], layers.get("m")
        return tuple(stability_flags(time, k, b, m, dynamics, 1.0 / self.rate, hand_loads()))

    def limit_text(self) -> str:
        """The output limit in the device's own units: mNm, or a share of full scale."""
        if self.link.info.kind == p.KIND_VIBROTACTILE:
            return f"max output {self.limits[0] * 100:.4g}% of full scale"
        return f"max torque {self.limits[0] * 1e3:.4g} mNm"

    def warnings(self) -> list[str]:
        """Sentences about values the host had to change before sending them."""
        out = []
        if self.zeroed:
            out.append(f"{self.zeroed} samples held NaN or infinite values and were sent as zero")
        if self.clamped:
            out.append(
                f"{self.clamped} values were clamped to the device's limits ({self.limit_text()})"
            )
        return out
