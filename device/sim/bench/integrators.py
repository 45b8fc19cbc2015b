"""Simulated knob: integrator error against the analytic spring-mass-damper, 1 kHz to 100 kHz.

A step of drive d from rest into J*th'' + (b_dev + B)*th' + K*th = d; the largest angle error
relative to the final angle d/K:
  - the sampled knob (firmware: torque from the sampled angle, held for a period) with each
    plant integrator; its error is mostly the sampling itself (first order in the period);
  - the continuous coupling (coefficients inside the ODE) with the exact segment solution (matrix
    exponential) and with stepping schemes, which shows where explicit schemes diverge.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
from scipy.linalg import expm

from device.sim import KnobParams, KnobPhysics
from timeline.bench.report import Table, figure, save
from timeline.plugins.device_protocol import CoefficientBlock, Hand

NAME = "integrators"
SUMMARY = "simulator integrators against the analytic response, 1 kHz to 100 kHz"
K, B, D, SPAN = 1.0, 2e-4, 0.02, 0.05  # N*m/rad, N*m*s/rad, N*m, s
TEXTBOOK = dict(quantum=0.0, coulomb=0.0, velocity_cutoff=0.0)
SAMPLED = ("zoh", "rk4", "semi-implicit", "euler")
CONTINUOUS = ("exact", "rk4", "semi-implicit", "euler")


def analytic(t: np.ndarray, inertia: float, damping: float) -> np.ndarray:
    """Step response of J*th'' + c*th' + K*th = D from rest (underdamped)."""
    wn, zeta = math.sqrt(K / inertia), damping / (2 * math.sqrt(K * inertia))
    wd = wn * math.sqrt(1 - zeta**2)
    decay = np.exp(-zeta * wn * t)
    return D / K * (1 - decay * (np.cos(wd * t) + zeta * wn / wd * np.sin(wd * t)))


def sampled_error(rate: float, integrator: str) -> float:
    """The firmware-sampled knob with one plant integrator."""
    p = KnobParams(rate=rate, **TEXTBOOK)
    knob = KnobPhysics(p, integrator=integrator)
    knob.start(Hand("free"))
    n = int(SPAN * rate)
    tel = knob.run_block(CoefficientBlock(np.full(n, D), np.full(n, K), np.full(n, B)))
    return float(np.max(np.abs(tel.angle - analytic(tel.time, p.inertia, p.viscous + B))) * K / D)


def continuous_error(rate: float, scheme: str) -> float:
    """The closed loop integrated as an ODE with step 1/rate by one scheme (inf if it diverges)."""
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


def run(quick: bool, out: Path) -> list[Table]:
    rates = [1e3, 1e4, 1e5] if quick else [1e3, 2e3, 5e3, 1e4, 2e4, 5e4, 1e5]
    wn = math.sqrt(K / KnobParams().inertia)
    table = Table(
        "Integrators: max |angle error| / (d/K), step of 20 mNm into K = 1 N*m/rad, "
        "B = 0.2 mNm*s/rad",
        ["rate Hz", "w*h"] + [f"sampled {s}" for s in SAMPLED] + [f"ODE {s}" for s in CONTINUOUS],
    )
    curves: dict[str, list[float]] = {}
    for rate in rates:
        row = [s for s in (sampled_error(rate, s) for s in SAMPLED)]
        row += [continuous_error(rate, s) for s in CONTINUOUS]
        for name, value in zip([f"sampled {s}" for s in SAMPLED] + [f"ODE {s}" for s in CONTINUOUS],
                               row, strict=True):  # fmt: skip
            curves.setdefault(name, []).append(value)
        table.rows.append([int(rate), wn / rate] + row)
    table.notes += [
        "sampled: the knob's firmware samples the angle and holds the torque for a period; its "
        "error is the sampling itself, first order in the period",
        "ODE: the coefficients inside the ODE; 'exact' is the matrix-exponential segment "
        "solution, inf means the scheme diverged",
    ]
    plot(rates, curves, out)
    return [table]


def plot(rates: list[float], curves: dict[str, list[float]], out: Path) -> None:
    fig, ax = figure(7.0, 4.5)
    markers = "osD^"
    for i, (name, values) in enumerate(curves.items()):
        shown = [v if math.isfinite(v) else np.nan for v in values]
        sampled = name.startswith("sampled")
        ax.plot(rates, np.maximum(shown, 1e-17), "-" if sampled else "--", color=f"C{i}",
                marker=markers[i % 4], ms=7 if sampled else 4, mfc="none" if sampled else None,
                label=name)  # fmt: skip
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("device rate (Hz)")
    ax.set_ylabel("max |angle error| / (d/K)")
    ax.set_title("Simulator integrators against the analytic step response", fontsize=10)
    ax.legend(
        fontsize=7, ncol=2, loc="lower left", title="identical curves overlap", title_fontsize=7
    )
    save(fig, out, "sim_integrators")
