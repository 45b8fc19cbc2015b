"""Simulated knob: how its velocity and acceleration estimates follow the motion, and their noise.

Gain and phase of the firmware's estimates against the true derivatives over frequency (ideal
sensor, steady state): the filter chain and the tracking observer (device/sim/observer.py); and
the torque noise a virtual mass makes from the quantised encoder while a hand turns the knob at
a constant speed, with each estimator (the observer at its default 1 kHz).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from device.sim import KnobParams, KnobPhysics, observer
from device.sim.estimator import acceleration_response, velocity_response
from timeline.bench.report import Table, figure, save
from timeline.devices import CoefficientBlock, Hand

NAME = "estimator"
SUMMARY = "simulated knob: velocity/acceleration estimate gain and phase, mass torque noise"
FREQUENCIES = (10.0, 50.0, 100.0, 175.0, 300.0, 500.0)
MASS = 1e-5  # kg*m^2: one full scale of the mass track
SPEEDS = (37.0, 90.0)  # deg/s: 3.7 and exactly 9 encoder counts per period
BANDWIDTHS = (300.0, 1000.0)  # Hz: the tracking observer's poles


def mass_noise(speed: float, seconds: float, estimator: str = "filter") -> float:
    """RMS torque (N*m) of a constant virtual mass while a hand turns the knob steadily."""
    knob = KnobPhysics(KnobParams(estimator=estimator))
    knob.start(Hand("turn", speed))
    n = int(seconds * knob.params.rate)
    zero = np.zeros(n)
    torque = knob.run_block(CoefficientBlock(zero, zero, zero, np.full(n, MASS))).torque
    steady = torque[n // 2 :]  # after the grip has settled
    return float(np.sqrt(np.mean((steady - steady.mean()) ** 2)))


def run(quick: bool, out: Path) -> list[Table]:
    p = KnobParams()
    vel, acc = velocity_response(p, FREQUENCIES), acceleration_response(p, FREQUENCIES)
    tracked = [observer.acceleration_response(p.period, b, FREQUENCIES) for b in BANDWIDTHS]
    response = Table(
        "Estimate against the true derivative (ideal sensor, steady state, 10 kHz): filters "
        f"{p.velocity_cutoff:g} Hz / {p.acceleration_cutoff:g} Hz, and the tracking observer",
        ["frequency [Hz]", "velocity gain", "velocity phase [deg]", "acceleration gain",
         "acceleration phase [deg]"]
        + [f"tracking {b:g} Hz: acceleration gain / phase [deg]" for b in BANDWIDTHS],
    )  # fmt: skip
    for i, (f, v, a) in enumerate(zip(FREQUENCIES, vel, acc, strict=True)):
        row = [f, abs(v), float(np.degrees(np.angle(v))), abs(a), float(np.degrees(np.angle(a)))]
        row += [f"{abs(h[i]):.3f} / {np.degrees(np.angle(h[i])):.1f}" for h in tracked]
        response.rows.append(row)
    noise = Table(
        f"Torque noise of a {MASS:g} kg*m^2 virtual mass, hand turning steadily (0.001 deg "
        "encoder; filters as above, tracking observer at 1000 Hz)",
        ["estimator", "speed [deg/s]", "counts per period", "torque noise [mNm rms]"],
    )
    for estimator in ("filter", "tracking"):
        for speed in SPEEDS:
            counts = np.radians(speed) / p.rate / p.quantum
            rms = mass_noise(speed, 1.0 if quick else 2.0, estimator)
            noise.rows.append([estimator, speed, float(counts), 1e3 * rms])
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
