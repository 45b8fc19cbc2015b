"""The `sim` device plugin: the simulated knob behind the host device protocol."""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import replace
from typing import Any

import numpy as np

from device.sim.params import KnobParams
from device.sim.physics import KnobPhysics
from timeline.plugins.device_protocol import (
    CoefficientBlock,
    Device,
    DeviceError,
    DeviceInfo,
    Hand,
    LatenessMeter,
    LiveTelemetry,
    Monitor,
    PositionProgram,
    Progress,
    Telemetry,
)

POSITION_CHUNK = 0.05  # s of a position program simulated between progress reports


class SimKnob(Device):
    """A simulated force-feedback knob (the paper's knob by default) with a hand model."""

    def __init__(self, integrator: str = "zoh", substeps: int = 1, **params: Any) -> None:
        self.params = KnobParams(**params)
        if self.params.max_torque == 0:
            raise DeviceError(
                "the simulated knob's max torque is its motor's own limit and must be above 0 "
                "N*m; to feel no torque, mute the tracks"
            )
        self.physics = KnobPhysics(self.params, integrator, substeps)

    @classmethod
    def options(cls) -> tuple[str, ...]:
        """The integrator, its substeps and every knob parameter (device.sim.params)."""
        return ("integrator", "substeps", *KnobParams.option_names())

    @property
    def info(self) -> DeviceInfo:
        p = self.params
        return DeviceInfo(
            "sim",
            "kinesthetic",
            p.rate,
            p.max_torque,
            p.quantum,
            p.firmware,
            p.dynamics,
            p.slew or None,
        )

    @classmethod
    def discover(cls) -> list[str]:
        p = KnobParams()
        return [
            f"simulated knob: {p.rate:g} Hz, {p.max_torque * 1e3:g} mNm, "
            f"{p.quantum * 180 / 3.141592653589793:g} deg encoder (always available)"
        ]

    def warm_up(self) -> None:
        """Load the compiled servo loop and the stability check's (from numba's cache) on a knob
        of its own. A block with no spring skips the check, so the first block of a play with
        one loaded the check's loop and scipy's expm on the playing thread: the first play's
        175-215 ms stall at 20,000 clips. Two samples with a spring and damping, the second
        unstable, go through every step of it (the eigenvalues too)."""
        knob = KnobPhysics(self.params)
        knob.start(Hand("hold"))
        spring = np.array([0.0, 1.0, 1e4])
        knob.run_block(CoefficientBlock(np.zeros(3), spring, np.array([0.0, 1e-3, 0.0])))

    def play(
        self,
        program: Iterable[CoefficientBlock] | PositionProgram,
        hand: Hand | None = None,
        progress: Progress | None = None,
        monitor: Monitor | None = None,
    ) -> Telemetry:
        """Play blocks (time mode) or a position program from the knob's current angle.

        A monitored time play (the editor's, which judges the design itself: its findings)
        leaves out the stability flags: judging each block took about 1 ms of the playing
        thread's 10 ms at 20,000 clips, and a thread that needs more than its share of a busy
        core waits for it (tens of ms at the ordinary priority).
        """
        self.physics.start(hand)
        judged = monitor is None
        parts: list[Telemetry] = []

        def keep(part: Telemetry) -> None:
            parts.append(part)
            if monitor and len(part):
                monitor(LiveTelemetry(part.time, part.angle, part.torque))

        if isinstance(program, PositionProgram):
            total_n = round(program.duration * self.params.rate)
            chunk = max(1, round(POSITION_CHUNK * self.params.rate))
            for n0 in range(0, total_n, chunk):
                keep(self.physics.run_table(program, min(chunk, total_n - n0)))
                if progress:
                    progress(self.physics.samples / self.params.rate, total_n / self.params.rate)
        else:
            total = len(program) if hasattr(program, "__len__") else None
            for i, block in enumerate(program):
                keep(self.physics.run_block(block, judged))
                if progress:
                    seconds = self.physics.samples / self.params.rate
                    progress(seconds, None if total is None else seconds * total / (i + 1))
                if self.physics.failed:
                    break
        if not parts:
            parts.append(self.physics.run_block(CoefficientBlock.zeros(0)))
        tel = Telemetry.concatenate(parts)
        meter = getattr(program, "lateness", None)  # a paced stream counts its late blocks
        return replace(tel, lateness=meter.counts()) if isinstance(meter, LatenessMeter) else tel
