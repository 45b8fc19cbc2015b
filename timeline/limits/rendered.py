"""Rendered against designed: what the device will output next to what was drawn.

* Vibration (a drive layer with an actuator, or a vibrotactile device): the drive clamped to the
  device's maximum, then through the actuator's response.
* A knob: the project played on the simulated knob built from the device's declarations (rate,
  maximum torque, rotor, delay, and the estimator it declares: filter cut-offs, or a Kalman or
  tracking observer with its own gains) with a hand (turning, on a position project);
  "designed" is the torque law evaluated on the motion that happened with exact (zero-phase)
  derivatives of the angle, "rendered" is the torque the motor applied: the difference is the
  clamp and the estimators' lag and noise.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from scipy.signal import savgol_filter

from timeline.errors import HapticTimelineError
from timeline.limits.design import Sampled
from timeline.limits.device_checks import actuator_output
from timeline.model import Project
from timeline.plugins.device_protocol import (
    Actuator,
    DeviceInfo,
    Hand,
    PositionProgram,
    open_device,
)
from timeline.plugins.device_protocol.hand import DEFAULT_TURN_DEG_PER_S
from timeline.rendering.playback import prepare

DERIVATIVE_WINDOW = 0.002  # s: the zero-phase fit the exact derivatives come from


@dataclass(frozen=True, eq=False)
class Trace:
    """One designed signal and its rendering, over time."""

    label: str
    unit: str  # display unit
    scale: float  # display value = SI value * scale
    time: np.ndarray
    designed: np.ndarray
    rendered: np.ndarray
    angle: np.ndarray | None = None  # position projects: the table angle (rad) of each sample
    step: float = 0.0  # axis units per cell to draw it in: a period, or the table's angle step

    @property
    def axis(self) -> str:
        """The project axis the trace is drawn along: "time" or "position" (its angle)."""
        return "time" if self.angle is None else "position"

    def worst_gap(self) -> float:
        """Largest |rendered - designed| (SI)."""
        return self._gap

    @cached_property
    def _gap(self) -> float:  # once: the editor asks at every zoom, for every lane
        return float(np.abs(self.rendered - self.designed).max(initial=0.0))


def vibration(design: Sampled, info: DeviceInfo, actuator: Actuator | None) -> Trace | None:
    """The drive after the device's clamp and the actuator's response."""
    d = design.terms.get("d")
    if d is None or design.axis != "time" or (actuator is None and info.kind != "vibrotactile"):
        return None
    clamped = np.clip(d, -info.max_output, info.max_output)
    out = actuator_output(actuator, clamped, design.rate) if actuator else clamped
    time = design.start + np.arange(d.size) / design.rate
    unit, scale = ("mNm", 1e3) if info.kind == "kinesthetic" else ("% full scale", 100.0)
    name = actuator.name if actuator else info.name
    return Trace(f"drive on {name}", unit, scale, time, d, out, step=1.0 / design.rate)


def knob(project: Project, info: DeviceInfo, hand: Hand, quality: str = "normal") -> Trace:
    """The torque law against the torque applied, on a simulated knob with the device's numbers.

    On a position project the hand turns the knob through the tables (at its own speed if it
    turns, else the same hand at the default speed), and the trace also holds the angle.
    """
    options: dict[str, object] = {"rate": info.rate, "max_torque": info.max_output}
    dyn, assumed = info.dynamics, ""
    if dyn is not None:
        options.update(inertia=dyn.inertia, viscous=dyn.damping, delay=int(dyn.delay),
                       velocity_cutoff=dyn.velocity_cutoff,
                       acceleration_cutoff=dyn.acceleration_cutoff)  # fmt: skip
        if dyn.estimator_declared:  # the estimator it declares, with the very gains it runs
            options.update(estimator=dyn.estimator, gains=dyn.observer_gains)
        else:
            assumed = " (estimator not declared: the sim's Kalman observer assumed)"
    if project.axis == "position" and hand.mode != "turn":
        hand = Hand("turn", DEFAULT_TURN_DEG_PER_S, model=hand.model)
    with open_device("sim", **options) as sim:
        playback = prepare(project, sim.info, None, hand, quality)
        tel = sim.play(playback.program, hand)
    if len(tel) < 8:
        raise HapticTimelineError("the design is too short to plot as it renders")
    window = min(len(tel) - (1 - len(tel) % 2), max(5, round(DERIVATIVE_WINDOW * tel.rate) | 1))
    period = 1.0 / tel.rate
    angle = tel.angle
    velocity = savgol_filter(tel.angle, window, 3, deriv=1, delta=period)
    acceleration = savgol_filter(tel.angle, window, 3, deriv=2, delta=period)
    zero = np.zeros(len(tel))
    layer = {k: tel.layers.get(k, zero) for k in "dkbm"}
    designed = layer["d"] - layer["k"] * angle - layer["b"] * velocity - layer["m"] * acceleration
    label = f"torque on {info.name}, hand {hand}{assumed}"
    program = playback.program
    if not isinstance(program, PositionProgram):  # a time project: blocks over time
        return Trace(label, "mNm", 1e3, tel.time, designed, tel.torque, step=period)
    angle = program.origin + tel.angle
    step = 1.0 / program.table_now().rate
    return Trace(label, "mNm", 1e3, tel.time, designed, tel.torque, angle, step)
