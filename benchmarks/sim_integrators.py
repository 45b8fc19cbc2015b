"""Simulated knob: integrator error against the analytic spring-mass-damper, and speed.

    python benchmarks/sim_integrators.py [--quick]

Part 1 steps J*th'' + (b_dev + B)*th' + K*th = d (a step of drive d from rest) and prints the
largest angle error relative to the final angle d/K, for device rates 1 kHz..100 kHz:
  - the sampled knob (firmware model: torque from the sampled angle, held for a period) with each
    plant integrator; its error is mostly the sampling itself (first order in the period);
  - the continuous coupling (coefficients inside the ODE) with the exact segment solution
    (matrix exponential) and with stepping schemes, which shows where explicit schemes diverge.
Part 2 times a 10 s icon with varying coefficients at 10 kHz on the paper's knob, as a multiple
of real time and as a ratio to a bare Python loop of the same length measured in this process.
"""

from __future__ import annotations

import argparse
import math
import time

import numpy as np
from scipy.linalg import expm

from device.sim import KnobParams, KnobPhysics
from timeline.devices import CoefficientBlock, Hand

K, B, D, SPAN = 1.0, 2e-4, 0.02, 0.05  # N*m/rad, N*m*s/rad, N*m, s
TEXTBOOK = dict(quantum=0.0, coulomb=0.0, velocity_cutoff=0.0)


def analytic(t: np.ndarray, inertia: float, damping: float) -> np.ndarray:
    """Step response of J*th'' + c*th' + K*th = D from rest (underdamped)."""
    wn, zeta = math.sqrt(K / inertia), damping / (2 * math.sqrt(K * inertia))
    wd = wn * math.sqrt(1 - zeta**2)
    decay = np.exp(-zeta * wn * t)
    return D / K * (1 - decay * (np.cos(wd * t) + zeta * wn / wd * np.sin(wd * t)))


def sampled_error(rate: float, integrator: str) -> float:
    p = KnobParams(rate=rate, **TEXTBOOK)
    knob = KnobPhysics(p, integrator=integrator)
    knob.start(Hand("free"))
    n = int(SPAN * rate)
    tel = knob.run_block(CoefficientBlock(np.full(n, D), np.full(n, K), np.full(n, B)))
    return float(np.max(np.abs(tel.angle - analytic(tel.time, p.inertia, p.viscous + B))) * K / D)


def continuous_error(rate: float, scheme: str) -> float:
    """The closed loop integrated as an ODE with step 1/rate by one scheme."""
    p = KnobParams()
    h, n = 1.0 / rate, int(SPAN * rate)
    a = np.array(
        [[0, 1, 0], [-K / p.inertia, -(p.viscous + B) / p.inertia, D / p.inertia], [0, 0, 0]]
    )
    eye = np.eye(3)
    if scheme == "exact":
        step = expm(a * h)
    elif scheme == "rk4":
        ha = h * a
        step = eye + ha @ (eye + ha @ (eye / 2 + ha @ (eye / 6 + ha / 24)))
    elif scheme == "semi-implicit":
        step = eye + h * a
        step[0] = eye[0] + h * step[1]
    else:
        step = eye + h * a
    z = np.array([0.0, 0.0, 1.0])
    out = np.empty(n)
    with np.errstate(all="ignore"):
        for i in range(n):
            out[i] = z[0]
            z = step @ z
    err = np.max(np.abs(out - analytic(np.arange(n) * h, p.inertia, p.viscous + B))) * K / D
    return float(err) if np.isfinite(err) else math.inf


def error_table(rates: list[float]) -> None:
    sampled = ["zoh", "rk4", "semi-implicit", "euler"]
    continuous = ["exact", "rk4", "semi-implicit", "euler"]
    head = ["rate Hz", "w*h"] + [f"samp:{s}" for s in sampled] + [f"cont:{s}" for s in continuous]
    print("max |angle error| / (d/K), step of d = 20 mNm into K = 1 N*m/rad, B = 0.2 mNm*s/rad")
    print(" ".join(f"{h:>14}" for h in head))
    wn = math.sqrt(K / KnobParams().inertia)
    for rate in rates:
        row = [f"{rate:>14.0f}", f"{wn / rate:>14.4f}"]
        row += [f"{sampled_error(rate, s):>14.3e}" for s in sampled]
        row += [f"{continuous_error(rate, s):>14.3e}" for s in continuous]
        print(" ".join(row))


def icon(seconds: float, rate: float, mass: bool) -> list[CoefficientBlock]:
    """A varying icon: a 5 Hz drive, a breathing spring, damping and (optionally) mass."""
    t = np.arange(int(seconds * rate)) / rate
    d = 0.05 * np.sin(2 * np.pi * 5 * t)
    k = 0.5 + 0.4 * np.sin(2 * np.pi * 0.5 * t)
    b = 5e-5 * (1 + np.sin(2 * np.pi * 3 * t))
    m = 2e-6 * (1 + np.sin(2 * np.pi * 1 * t)) if mass else None
    size = int(0.1 * rate)
    return [
        CoefficientBlock(
            d[i : i + size],
            k[i : i + size],
            b[i : i + size],
            None if m is None else m[i : i + size],
        )  # fmt: skip
        for i in range(0, t.size, size)
    ]


def bare_loop(n: int) -> float:
    """Seconds for a Python loop of n iterations doing one multiply-add (the baseline)."""
    x, start = 0.0, time.perf_counter()
    for i in range(n):
        x = x * 0.5 + i
    return time.perf_counter() - start


def speed(seconds: float) -> None:
    rate = 10_000.0
    n = int(seconds * rate)
    print(f"\nspeed: {seconds:g} s icon at {rate:g} Hz, paper's knob, best of 3")
    print(f"{'case':>28} {'x real time':>12} {'per step us':>12} {'/ bare loop step':>17}")
    for hand in ("hold", "turn:90", "free"):
        for mass in (False, True):
            blocks = icon(seconds, rate, mass)
            best, base = math.inf, math.inf
            for _ in range(3):
                knob = KnobPhysics()
                knob.start(Hand.parse(hand))
                start = time.perf_counter()
                for blk in blocks:
                    knob.run_block(blk)
                best = min(best, time.perf_counter() - start)
                base = min(base, bare_loop(n))
            case = f"hand {hand}, {'with' if mass else 'no'} mass"
            print(
                f"{case:>28} {seconds / best:>12.0f} {best / n * 1e6:>12.2f} {best / base:>17.1f}"
            )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer rates and a 1 s icon (CI)")
    args = parser.parse_args()
    rates = [1e3, 1e4, 1e5] if args.quick else [1e3, 2e3, 5e3, 1e4, 2e4, 5e4, 1e5]
    error_table(rates)
    speed(1.0 if args.quick else 10.0)


if __name__ == "__main__":
    main()
