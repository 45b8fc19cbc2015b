"""Generator shapes: closed-form functions of position u (seconds or radians), exact at any rate.

Each generator may name the parameter values it cannot render (`GeneratorSpec.check`): one
sentence naming the parameter, which a tile raises when it is made or read.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass

import numpy as np

from timeline.signal.vibration_design import emphasis_length, emphasis_pulse

TWO_PI = 2.0 * np.pi


@dataclass(frozen=True)
class GeneratorSpec:
    """A generator's name, parameter defaults, and function f(u, duration, **params).

    `length`, for a shape that lasts a time its parameters set (an emphasis: two cycles of its
    carrier), gives that time; its tiles are that long. `check(params, duration)` gives the
    sentence that refuses parameters the shape cannot render, or None.
    """

    name: str
    defaults: Mapping[str, float]
    function: Callable[..., np.ndarray]
    summary: str
    length: Callable[[Mapping[str, float]], float] | None = None
    check: Callable[[Mapping[str, float], float], str | None] | None = None


def _sine(u, duration, frequency, phase, amplitude):
    return amplitude * np.sin(TWO_PI * frequency * u + phase)


def _cycle_position(u, frequency, phase):
    """Fractional position within the current cycle, in [0, 1)."""
    x = frequency * u + phase / TWO_PI
    return x - np.floor(x)


def _square(u, duration, frequency, phase, amplitude, duty):
    return amplitude * np.where(_cycle_position(u, frequency, phase) < duty, 1.0, -1.0)


def _triangle(u, duration, frequency, phase, amplitude):
    x = _cycle_position(u, frequency, phase)
    return amplitude * (1.0 - 4.0 * np.abs(x - 0.5))


def _saw(u, duration, frequency, phase, amplitude):
    return amplitude * (2.0 * _cycle_position(u, frequency, phase) - 1.0)


def _chirp(u, duration, f0, f1, amplitude, exponential):
    if exponential:  # f0, f1 > 0 (_check_chirp)
        if f0 == f1:
            phase = TWO_PI * f0 * u
        else:
            rate = np.log(f1 / f0) / duration
            phase = TWO_PI * f0 * np.expm1(rate * u) / rate
    else:
        phase = TWO_PI * (f0 * u + 0.5 * (f1 - f0) * u * u / duration)
    return amplitude * np.sin(phase)


def _ramp(u, duration, start, end):
    return start + (end - start) * (u / duration)


def _constant(u, duration, value):
    return np.full(np.shape(u), float(value))


_GOLDEN = np.uint64(0x9E3779B97F4A7C15)


def _hash_unit(index: np.ndarray, seed: int) -> np.ndarray:
    """A splitmix64 hash of integer lattice indices mapped to uniform values in [-1, 1)."""
    with np.errstate(over="ignore"):
        z = index.astype(np.uint64) * _GOLDEN + np.uint64(seed & 0xFFFFFFFFFFFFFFFF)
        z = (z ^ (z >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
        z = (z ^ (z >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
        z = z ^ (z >> np.uint64(31))
    return (z >> np.uint64(11)).astype(np.float64) * (2.0 / 2.0**53) - 1.0


def _noise(u, duration, seed, bandwidth, amplitude):
    """Seeded value noise: random lattice values every 1/(2*bandwidth), joined by a smooth step.

    Its power spectrum is the lattice's white spectrum times |H|^2 (noise_spectrum); rendered at
    a Nyquist frequency below `bandwidth`, timeline.signal.band_limit takes white_noise instead.
    """
    x = np.asarray(u, dtype=np.float64) * (2.0 * bandwidth)
    i = np.floor(x)
    f = x - i
    w = f * f * (3.0 - 2.0 * f)
    idx = i.astype(np.int64)
    a = _hash_unit(idx, int(seed))
    b = _hash_unit(idx + 1, int(seed))
    return amplitude * (a + (b - a) * w)


def noise_spectrum(xi: np.ndarray) -> np.ndarray:
    """H(xi), the Fourier transform of the smooth step joining lattice values (h(x) = 1 - 3x^2 +
    2|x|^3 on |x| <= 1), at xi cycles per lattice step: 24 (1 - cos w)/w^4 - 12 sin(w)/w^3 with
    w = 2 pi xi, by its series 1 - w^2/15 + w^4/560 near 0 (where the closed form cancels)."""
    w = TWO_PI * np.abs(np.asarray(xi, dtype=np.float64))
    small = w < 0.05
    safe = np.where(small, 1.0, w)
    closed = 24.0 * (1.0 - np.cos(safe)) / safe**4 - 12.0 * np.sin(safe) / safe**3
    return np.where(small, 1.0 - w * w / 15.0 + w**4 / 560.0, closed)


def noise_level_below(bandwidth: float, nyquist: float) -> float:
    """RMS of value noise's part below `nyquist`, over a lattice value's RMS (for bandwidth above
    nyquist): sqrt(P(c)), P(c) = the integral of |H(xi)|^2 over |xi| < c = nyquist/(2 bandwidth)
    (Gauss-Legendre, 64 nodes: H^2 is smooth). P(1/2) = 0.684, P(c) -> 2c for small c."""
    from numpy.polynomial.legendre import leggauss  # 22 ms to import: only when needed

    nodes, weights = leggauss(64)
    c = nyquist / (2.0 * bandwidth)
    xi = 0.5 * c * (nodes + 1.0)
    power = c * float(np.sum(weights * noise_spectrum(xi) ** 2))  # 2 * (c/2) * sum
    return math.sqrt(power)


def white_noise(u: np.ndarray, seed: float, lattice: float, level: float) -> np.ndarray:
    """Value noise band-limited to Nyquist: one lattice value per sample (lattice = the sample
    rate in u's units, the value nearest u * lattice), times `level`: white up to Nyquist."""
    index = np.floor(np.asarray(u, dtype=np.float64) * lattice + 0.5).astype(np.int64)
    return level * _hash_unit(index, int(seed))


def _detents(u, duration, count, amplitude, phase):
    """A detent series: restoring torque -sin with `count` stable rest points over the tile."""
    period = duration / count
    return -amplitude * np.sin(TWO_PI * (u - phase * period) / period)


def _wall(u, duration, edge, width, direction):
    """A wall: zero before `edge` (fraction of the tile), then a spring over `width`."""
    depth = np.clip((u / duration - edge) / max(width, 1e-300), 0.0, 1.0)
    return -np.sign(direction) * depth if direction else -depth


def _stribeck(u, duration, static, coulomb, stribeck_velocity, viscous, velocity_range):
    """Stribeck friction against velocity: the tile spans velocities -range..+range."""
    v = (2.0 * u / duration - 1.0) * velocity_range
    level = coulomb + (static - coulomb) * np.exp(-((v / stribeck_velocity) ** 2))
    return np.sign(v) * level + viscous * v


def _adsr(u, duration, attack, decay, sustain, release):
    """An ADSR envelope with times in the tile's units; release ends at the tile's end."""
    u = np.asarray(u, dtype=np.float64)
    release_start = duration - release
    out = np.full(u.shape, float(sustain))
    if attack > 0:
        m = u < attack
        out[m] = u[m] / attack
    if decay > 0:
        m = (u >= attack) & (u < attack + decay)
        out[m] = 1.0 - (1.0 - sustain) * (u[m] - attack) / decay
    if release > 0:
        m = u >= release_start
        out[m] = sustain * np.clip((duration - u[m]) / release, 0.0, 1.0)
    out[(u < 0) | (u > duration)] = 0.0
    return out


def _am(u, duration, carrier, modulation, depth, amplitude):
    envelope = (1.0 + depth * np.sin(TWO_PI * modulation * u)) / (1.0 + abs(depth))
    return amplitude * envelope * np.sin(TWO_PI * carrier * u)


def _emphasis(u, duration, amplitude, frequency):
    return emphasis_pulse(u, amplitude, frequency)


# A noise's lattice points over its tile at most: beyond, u * 2 * bandwidth keeps too few bits
# of the fraction between them (at 2**52 none), and the lattice index nears int64's range.
MAX_NOISE_LATTICE = 2.0**40


def _nonzero(
    generator: str, name: str, why: str
) -> Callable[[Mapping[str, float], float], str | None]:
    """A check that parameter `name` is not 0 (`why`: what it does, for the sentence)."""

    def check(p: Mapping[str, float], duration: float) -> str | None:
        return None if p[name] != 0 else f"a {generator} tile's {name} must not be 0 ({why})"

    return check


def _check_chirp(p: Mapping[str, float], duration: float) -> str | None:
    for name in ("f0", "f1"):
        if p["exponential"] and p[name] <= 0:
            return (
                f"an exponential chirp's {name} must be above 0, not {p[name]:g} (a sweep by "
                "a constant factor never reaches 0; use a linear chirp, exponential 0)"
            )
    return None


def _check_noise(p: Mapping[str, float], duration: float) -> str | None:
    bandwidth = p["bandwidth"]
    if bandwidth <= 0:
        return f"a noise's bandwidth must be above 0, not {bandwidth:g}"
    if 2.0 * bandwidth * duration > MAX_NOISE_LATTICE:
        most = MAX_NOISE_LATTICE / (2.0 * duration)
        return (
            f"a noise's bandwidth must be at most {most:.3g} for a tile of {duration:g}, not "
            f"{bandwidth:g} (a render keeps only what is below its Nyquist frequency anyway)"
        )
    return None


GENERATORS: dict[str, GeneratorSpec] = {
    s.name: s
    for s in [
        GeneratorSpec("sine", {"frequency": 10.0, "phase": 0.0, "amplitude": 1.0}, _sine, "sine"),
        GeneratorSpec(
            "square",
            {"frequency": 10.0, "phase": 0.0, "amplitude": 1.0, "duty": 0.5},
            _square,
            "square wave with a duty cycle",
        ),
        GeneratorSpec(
            "triangle", {"frequency": 10.0, "phase": 0.0, "amplitude": 1.0}, _triangle, "triangle"
        ),
        GeneratorSpec(
            "saw", {"frequency": 10.0, "phase": 0.0, "amplitude": 1.0}, _saw, "rising sawtooth"
        ),
        GeneratorSpec(
            "chirp",
            {"f0": 10.0, "f1": 100.0, "amplitude": 1.0, "exponential": 0.0},
            _chirp,
            "frequency sweep from f0 to f1 over the tile",
            check=_check_chirp,
        ),
        GeneratorSpec("ramp", {"start": 0.0, "end": 1.0}, _ramp, "straight line from start to end"),
        GeneratorSpec("constant", {"value": 1.0}, _constant, "constant level"),
        GeneratorSpec(
            "noise",
            {"seed": 0.0, "bandwidth": 100.0, "amplitude": 1.0},
            _noise,
            "seeded band-limited value noise",
            check=_check_noise,
        ),
        GeneratorSpec(
            "detents",
            {"count": 4.0, "amplitude": 1.0, "phase": 0.0},
            _detents,
            "series of detents (stable rest points)",
            check=_nonzero("detents", "count", "the detents are duration / count apart"),
        ),
        GeneratorSpec(
            "wall", {"edge": 0.0, "width": 1.0, "direction": 1.0}, _wall, "spring wall past an edge"
        ),
        GeneratorSpec(
            "stribeck",
            {
                "static": 1.0,
                "coulomb": 0.6,
                "stribeck_velocity": 0.1,
                "viscous": 0.2,
                "velocity_range": 1.0,
            },
            _stribeck,
            "Stribeck friction curve over velocity",
            check=_nonzero("stribeck", "stribeck_velocity", "velocities are divided by it"),
        ),
        GeneratorSpec(
            "adsr",
            {"attack": 0.01, "decay": 0.02, "sustain": 0.6, "release": 0.05},
            _adsr,
            "attack-decay-sustain-release envelope",
        ),
        GeneratorSpec(
            "am",
            {"carrier": 175.0, "modulation": 8.0, "depth": 1.0, "amplitude": 1.0},
            _am,
            "amplitude-modulated carrier",
        ),
        GeneratorSpec(
            "emphasis",
            {"amplitude": 1.0, "frequency": 0.5},
            _emphasis,
            "vibration emphasis: two carrier cycles at a frequency of 0..1 (80..230 Hz)",
            lambda p: emphasis_length(p["frequency"]),
        ),
    ]
}
