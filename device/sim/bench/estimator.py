"""Simulated knob: how its velocity and acceleration estimates follow the motion, and their noise.

Gain and phase of the firmware's estimates against the true derivatives over frequency (ideal
sensor, steady state), computed from each estimator's matrices: the velocity filter, and the
acceleration from the Kalman observer (the default), the filter chain and the tracking observer
(device/sim/observer.py). Then the torque noise a virtual mass makes from the quantised encoder:
computed for white quantisation noise (sigma = quantum/sqrt(12)) and measured in the sim while a
hand turns the knob at a constant speed.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from device.sim import KnobParams, KnobPhysics, observer
from device.sim.estimator import acceleration_noise, acceleration_response, velocity_response
from timeline.bench.report import Table, figure, save
from timeline.plugins.device_protocol import ESTIMATORS, CoefficientBlock, Hand

NAME = "estimator"
SUMMARY = "simulated knob: velocity/acceleration estimate gain and phase, mass torque noise"
FREQUENCIES = (10.0, 50.0, 100.0, 175.0, 300.0, 500.0)
MASS = 1e-5  # kg*m^2: one full scale of the mass track
SPEEDS = (37.0, 90.0)  # deg/s: 3.7 and exactly 9 encoder counts per period
BANDS = (1.0, 10.0, 20.0, 50.0, 100.0, 150.0, 200.0)  # deg/s: the speed table's bands


def mass_noise(speed: float, seconds: float, estimator: str = "kalman") -> float:
    """RMS torque (N*m) of a constant virtual mass while a hand turns the knob steadily."""
    knob = KnobPhysics(KnobParams(estimator=estimator))
    knob.start(Hand("turn", speed))
    n = int(seconds * knob.params.rate)
    zero = np.zeros(n)
    torque = knob.run_block(CoefficientBlock(zero, zero, zero, np.full(n, MASS))).torque
    steady = torque[n // 2 :]  # after the grip has settled
    return float(np.sqrt(np.mean((steady - steady.mean()) ** 2)))


def acceleration(estimator: str, frequency) -> np.ndarray:  # noqa: ANN001
    """Estimated over true acceleration at frequencies (Hz) for a named estimator."""
    p = KnobParams(estimator=estimator)
    if p.observer_gains is None:
        return acceleration_response(p, frequency)
    return observer.acceleration_response(p.period, p.observer_gains, frequency)


def white_noise(estimator: str) -> float:
    """RMS acceleration estimate (rad/s^2) for white quantisation noise at the default encoder."""
    p = KnobParams(estimator=estimator)
    sigma = p.quantum / np.sqrt(12.0)
    if p.observer_gains is not None:
        return observer.acceleration_noise(p.period, p.observer_gains, sigma)
    return acceleration_noise(p, sigma)


def _cell(h: complex) -> str:
    return f"{abs(h):.3f} / {np.degrees(np.angle(h)):.1f}"


def run(quick: bool, out: Path) -> list[Table]:
    p = KnobParams()
    vel = velocity_response(p, FREQUENCIES)
    acc = {name: acceleration(name, FREQUENCIES) for name in ESTIMATORS}
    response = Table(
        "Estimate against the true derivative, gain / phase [deg] (ideal sensor, steady state, "
        f"10 kHz): velocity filter {p.velocity_cutoff:g} Hz; acceleration from the Kalman "
        f"observer (noise {p.observer_noise:g} of a 3-point estimate's), the filter "
        f"({p.acceleration_cutoff:g} Hz) and the tracking observer ({p.observer_bandwidth:g} Hz)",
        ["frequency [Hz]", "velocity"] + [f"acceleration, {name}" for name in ESTIMATORS],
    )
    for i, f in enumerate(FREQUENCIES):
        response.rows.append([f, _cell(vel[i])] + [_cell(acc[name][i]) for name in ESTIMATORS])
    noise = Table(
        f"Torque noise of a {MASS:g} kg*m^2 virtual mass from the 0.001 deg encoder: computed "
        "for white quantisation noise, and measured with a hand turning the knob steadily",
        ["estimator", "white noise [mNm rms]", "speed [deg/s]", "counts per period",
         "measured [mNm rms]"],
    )  # fmt: skip
    for name in ESTIMATORS:
        white = 1e3 * MASS * white_noise(name)
        for speed in SPEEDS:
            counts = np.radians(speed) / p.rate / p.quantum
            rms = mass_noise(speed, 1.0 if quick else 2.0, name)
            noise.rows.append([name, white, speed, float(counts), 1e3 * rms])
    noise.notes.append("a whole number of counts per period repeats exactly: no noise")
    by_speed = speed_table(np.arange(1.0, 200.01, 3.1 if quick else 0.5), 1.0)
    f = np.geomspace(1.0, 2000.0, 200)
    fig, (ax_gain, ax_phase) = figure(7.0, 5.0, ncols=2)
    curves = {"velocity": velocity_response(p, f)}
    curves.update({f"acceleration, {name}": acceleration(name, f) for name in ESTIMATORS})
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
    return [response, noise, by_speed]


def speed_table(grid: np.ndarray, seconds: float) -> Table:
    """Measured mass torque noise per estimator over bands of the hand's turning speed: the
    median and the worst (with its speed) over the speeds of `grid` (deg/s) in each band. The
    noise depends on the speed (how the quantisation errors repeat; a whole number of counts
    per period gives none), so no one speed's figure bounds it."""
    table = Table(
        f"Measured torque noise of a {MASS:g} kg*m^2 virtual mass against the hand's turning "
        f"speed, median / worst (at deg/s) [mNm rms] (default knob, {seconds:g} s per speed, "
        f"second half; speeds every {grid[1] - grid[0]:g} deg/s from {grid[0]:g})",
        ["speeds [deg/s]", *ESTIMATORS],
    )
    measured = {name: np.array([mass_noise(s, seconds, name) for s in grid]) for name in ESTIMATORS}
    for lo, hi in zip(BANDS[:-1], BANDS[1:], strict=True):
        inside = (grid >= lo) & (grid < hi) if hi < BANDS[-1] else (grid >= lo) & (grid <= hi)
        if not inside.any():
            continue
        cells = []
        for name in ESTIMATORS:
            values = 1e3 * measured[name][inside]
            at = int(np.argmax(values))
            cells.append(f"{np.median(values):.3f} / {values[at]:.3f} (at {grid[inside][at]:g})")
        table.rows.append([f"{lo:g}-{hi:g}"] + cells)
    return table
