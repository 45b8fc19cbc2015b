"""Device findings: torque saturation, stiffness/damping/mass stability, slew, actuator band."""

from __future__ import annotations

from collections.abc import Callable
from typing import cast

import numpy as np
from scipy.signal import butter, iirpeak, lfilter

from timeline.limits import servo
from timeline.limits.design import Sampled
from timeline.limits.findings import Finding, spans
from timeline.limits.frames import frames
from timeline.limits.thresholds import AMPLITUDE_JND_DB
from timeline.plugins.device_protocol import Actuator, DeviceInfo, Dynamics

JOIN = 0.05  # s (rad on a position axis): crossings closer than this are one finding


def _over(
    design: Sampled,
    kind: str,
    layer: str,
    excess: np.ndarray,
    values: np.ndarray,
    limits: np.ndarray,
    unit: str,
    what: str,
    advice: Callable[[float, float], str],
) -> list[Finding]:
    """One finding per run of samples with excess > 0 (runs closer than JOIN count as one);
    value/limit at the run's worst sample."""
    out = []
    for a, b in spans(excess > 0, join=round(JOIN * design.rate)):
        worst = a + int(np.argmax(excess[a : b + 1]))
        value, limit = float(values[worst]), float(limits[worst])
        out.append(
            Finding(
                kind,
                "device",
                what,
                design.position(a),
                design.position(b + 1),
                design.axis,
                value,
                limit,
                unit,
                advice(value, limit),
                layer,
            )  # fmt: skip
        )
    return out


def _factor(f: float) -> str:
    """A scale factor for advice: two decimals, or two significant digits below 0.01."""
    return f"{f:.2f}" if f >= 0.01 else f"{f:.2g}"


def saturation(design: Sampled, info: DeviceInfo) -> list[Finding]:
    """|d| (drive, or the position torque table) beyond the device's maximum output."""
    d = design.terms.get("d")
    if d is None:
        return []
    limit = np.full(d.size, info.max_output)
    unit = "N*m" if info.kind == "kinesthetic" else "of full scale"
    return _over(
        design, "torque-saturation", "d", np.abs(d) - limit, np.abs(d), limit, unit,
        f"the {design.names['d']} layer asks for more than the device's maximum output",
        lambda v, lim: f"scale that part by {_factor(lim / v)} or less (clip or track gain)",
    )  # fmt: skip


def local_stiffness(design: Sampled) -> np.ndarray:
    """Position projects: -dT/dtheta of the torque table (the spring the hand feels)."""
    d = design.terms.get("d")
    if d is None or d.size < 2:
        return np.zeros(design.length)
    slope = -np.diff(d) * design.rate
    return np.append(slope, slope[-1])


def stability(
    design: Sampled, info: DeviceInfo, interrupt: Callable[[], None] = lambda: None
) -> list[Finding]:
    """Stiffness above passivity, damping above its stable limit or negative, mass out of band;
    `interrupt` is called between pieces of the whole-loop test (a stale check stops there)."""
    dyn = info.dynamics
    if dyn is None or info.kind != "kinesthetic" or not design.length:
        return []
    period = info.period
    n = design.length
    zero = np.zeros(n)
    b = design.terms.get("b", zero)
    k = local_stiffness(design) if design.axis == "position" else design.terms.get("k", zero)
    out = []
    k_pass = servo.passive_stiffness(dyn.damping, b, period, dyn.delay)
    out += _over(
        design, "stiffness-limit", "k", np.where(k > 0, k - k_pass, 0.0), k, k_pass, "N*m/rad",
        "stiffness above the largest the device renders passively at its rate and damping",
        lambda v, lim: f"keep the stiffness below {lim:.3g} N*m/rad (lower the gain, or the "
        "damping that eats into the margin)",
    )  # fmt: skip
    out += _over(
        design, "negative-damping", "b", -b, b, zero, "N*m*s/rad",
        "negative virtual damping: the device pushes energy into the hand",
        lambda v, lim: "make the damping zero or positive there",
    )  # fmt: skip
    declared = dyn.estimator_declared  # the damping and mass limits depend on the estimator
    if declared:
        b_max = servo.damping_limit(dyn, period)
        out += _over(
            design, "damping-limit", "b", b - b_max, b, np.full(n, b_max), "N*m*s/rad",
            "virtual damping above the largest the servo loop renders without chatter",
            lambda v, lim: f"keep the damping below {lim:.3g} N*m*s/rad",
        )  # fmt: skip
    m = design.terms.get("m")
    if m is not None:
        cancel = dyn.inertia + m <= 0
        out += _over(
            design, "mass-cancels-inertia", "m", np.where(cancel, 1.0, 0.0), m,
            np.full(n, -dyn.inertia), "kg*m^2",
            "negative virtual mass cancels the rotor's inertia",
            lambda v, lim: f"keep the mass above {lim:.3g} kg*m^2",
        )  # fmt: skip
    if m is not None and declared:
        low, high = servo.mass_limits(dyn, period)
        excess = np.where(cancel, 0.0, np.maximum(m - high, low - m))
        out += _over(
            design, "mass-limit", "m", excess, m, np.where(m > high, high, low), "kg*m^2",
            "virtual mass outside the band the servo loop renders without chatter",
            lambda v, lim: f"keep the mass between {low:.3g} and {high:.3g} kg*m^2",
        )  # fmt: skip
    if declared:
        out += whole_loop(design, dyn, period, k, b, m, interrupt)
    return out


def whole_loop(
    design: Sampled,
    dyn: Dynamics,
    period: float,
    k: np.ndarray,
    b: np.ndarray,
    m: np.ndarray | None,
    interrupt: Callable[[], None] = lambda: None,
) -> list[Finding]:
    """Spans where every layer is inside its own limit but the loop with all of them is
    unstable with one of the docs' hands on the knob (or none): servo.whole_loop. The growth
    is found only where every layer is inside (elsewhere their own findings speak)."""
    inside = servo.layers_inside(dyn, period, k, b, m)
    loop = servo.whole_loop(dyn, period, k, b, m, servo.hand_loads(), interrupt, inside)
    bad = loop.any & inside
    if not bad.any():
        return []
    hands = ", ".join(name for name, where in loop.unstable.items() if (where & bad).any())
    radius = np.where(bad, loop.radius, 1.0)
    return _over(
        design, "unstable-loop", "", radius - 1.0, radius, np.ones(design.length),
        "growth per period",
        "stiffness, damping and mass each inside their own limit, but together they make the "
        f"servo loop unstable (with the {hands})",
        lambda v, lim: "lower the damping or the mass there (or the stiffness): each takes "
        "margin from the others",
    )  # fmt: skip


def slew(design: Sampled, info: DeviceInfo) -> list[Finding]:
    """Time projects: drive changing faster than the device's declared slew limit."""
    d = design.terms.get("d")
    if info.slew is None or d is None or design.axis != "time" or d.size < 2:
        return []
    rate = np.abs(np.diff(d, prepend=0.0)) * design.rate  # the device starts from rest
    limit = np.full(d.size, info.slew)
    return _over(
        design, "slew-limit", "d", rate - limit, rate, limit, "per s",
        "the drive changes faster than the device can follow",
        lambda v, lim: f"lengthen that edge by {v / lim:.1f}x (a fade or a smoother tile)",
    )  # fmt: skip


def actuator_output(actuator: Actuator, drive: np.ndarray, rate: float) -> np.ndarray:
    """What the actuator makes of a drive signal (its frequency response, peak gain 1)."""
    nyquist = rate / 2.0
    if actuator.type == "lra":
        if actuator.resonance >= nyquist:
            return np.zeros_like(drive)
        b, a = iirpeak(actuator.resonance, actuator.q, fs=rate)
    else:
        band = [actuator.low, min(actuator.high, 0.99 * nyquist)]
        # scipy is unannotated: pyright infers the union of every output= form (zpk, sos, None)
        b, a = cast(tuple[np.ndarray, np.ndarray], butter(2, band, "bandpass", fs=rate))
    return np.asarray(lfilter(b, a, drive))  # y alone: no zi, so no (y, zf) pair


def settling_time(actuator: Actuator) -> float:
    """Seconds the actuator takes to ring up or down (3 time constants)."""
    if actuator.type == "lra":
        return 3.0 * actuator.q / (np.pi * actuator.resonance)
    return 3.0 / (2.0 * np.pi * actuator.low)


def actuator_band(design: Sampled, info: DeviceInfo, actuator: Actuator | None) -> list[Finding]:
    """Parts where the actuator renders the drive more than an amplitude JND weaker than drawn.

    That happens where the drive's energy lies outside the actuator's band. Runs shorter than
    the actuator's settling time are its ring-up at an onset, not a band problem, and are left.
    """
    d = design.terms.get("d")
    if actuator is None or d is None or design.axis != "time":
        return []
    drawn = frames(np.clip(d, -info.max_output, info.max_output), design.rate, design.start)
    made = frames(actuator_output(actuator, d, design.rate), design.rate, design.start)
    active = drawn.rms > 1e-6 * info.max_output
    with np.errstate(divide="ignore"):
        loss = np.where(active, 20.0 * np.log10(drawn.rms / np.maximum(made.rms, 1e-300)), 0.0)
    shortest = settling_time(actuator)
    lo, hi = actuator.band()
    out = []
    for a, b in spans(loss > AMPLITUDE_JND_DB):
        start, stop = drawn.span(a, b)
        if stop - start < shortest:
            continue
        typical = float(np.median(loss[a : b + 1]))  # the ring-up at onsets is not the band
        freq = float(np.median(drawn.frequency[a : b + 1]))
        out.append(
            Finding(
                "outside-actuator-band", "device",
                f"energy outside the {actuator.describe()}: it renders this part (near "
                f"{freq:.0f} Hz) weaker than drawn", start, stop, "time", typical,
                AMPLITUDE_JND_DB, "dB", f"move the energy into {lo:.0f}-{hi:.0f} Hz or choose "
                "a wideband actuator", "d",
            )
        )  # fmt: skip
    return out
