"""Simulated knob: how its velocity and acceleration estimates follow the motion, and their noise.

Gain and phase of the firmware's estimates against the true derivatives over frequency (ideal
sensor, steady state, from the filter chain), and the torque noise a virtual mass makes from the
quantised encoder while a hand turns the knob at a constant speed.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from device.sim import KnobParams, KnobPhysics
from device.sim.estimator import acceleration_response, velocity_response
from timeline.bench.report import Table, figure, save
from timeline.devices import CoefficientBlock, Hand

NAME = "estimator"
SUMMARY = "simulated knob: velocity/acceleration estimate gain and phase, mass torque noise"
FREQUENCIES = (10.0, 50.0, 100.0, 175.0, 300.0, 500.0)
MASS = 1e-5  # kg*m^2: one full scale of the mass track
SPEEDS = (37.0, 90.0)  # deg/s: 3.7 and exactly 9 encoder counts per period


def mass_noise(speed: float, seconds: float) -> float:
    """RMS torque (N*m) of a constant virtual mass while a hand turns the knob steadily."""
    knob = KnobPhysics(KnobParams())
    knob.start(Hand("turn", speed))
    n = int(seconds * knob.params.rate)
    zero = np.zeros(n)
    torque = knob.run_block(CoefficientBlock(zero, zero, zero, np.full(n, MASS))).torque
    steady = torque[n // 2 :]  # after the grip has settled
    return float(np.sqrt(np.mean((steady - steady.mean()) ** 2)))


def run(quick: bool, out: Path) -> list[Table]:
    p = KnobParams()
    vel, acc = velocity_response(p, FREQUENCIES), acceleration_response(p, FREQUENCIES)
    response = Table(
        "Estimate against the true derivative (ideal sensor, steady state, 10 kHz, filters "
        f"{p.velocity_cutoff:g} Hz / {p.acceleration_cutoff:g} Hz)",
        [
            "frequency [Hz]",
            "velocity gain",
            "velocity phase [deg]",
            "acceleration gain",
            "acceleration phase [deg]",
        ],  # fmt: skip
    )
    for f, v, a in zip(FREQUENCIES, vel, acc, strict=True):
        response.rows.append([f, abs(v), float(np.degrees(np.angle(v))), abs(a),
                              float(np.degrees(np.angle(a)))])  # fmt: skip
    noise = Table(
        f"Torque noise of a {MASS:g} kg*m^2 virtual mass, hand turning steadily (0.001 deg "
        "encoder, default filters)",
        ["speed [deg/s]", "counts per period", "torque noise [mNm rms]"],
    )
    for speed in SPEEDS:
        counts = np.radians(speed) / p.rate / p.quantum
        noise.rows.append([speed, float(counts), 1e3 * mass_noise(speed, 1.0 if quick else 2.0)])
    noise.notes.append("a whole number of counts per period repeats exactly: no noise")
    f = np.geomspace(1.0, 2000.0, 200)
    fig, (ax_gain, ax_phase) = figure(7.0, 5.0, ncols=2)
    curves = {"velocity": velocity_response(p, f), "acceleration": acceleration_response(p, f)}
    for name, h in curves.items():
        ax_gain.semilogx(f, np.abs(h), label=name)
        ax_phase.semilogx(f, np.degrees(np.angle(h)), label=name)
    ax_gain.set_ylabel("estimate / true")
    ax_phase.set_ylabel("phase [deg]")
    for ax in (ax_gain, ax_phase):
        ax.set_xlabel("frequency [Hz]")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    save(fig, out, "estimator")
    return [response, noise]
