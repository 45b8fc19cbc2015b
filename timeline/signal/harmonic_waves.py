"""Square, saw and triangle waves as Fourier series: exact band-limited synthesis at any rate.

With x the position within the cycle (frequency*u + phase/2pi) and K harmonics kept:

    square (duty d) = (2d - 1) + sum_k 2/(pi k) [sin(2 pi k x) - sin(2 pi k (x - d))]
    saw             = -sum_k 2/(pi k) sin(2 pi k x)
    triangle        = -sum_(k odd) 8/(pi^2 k^2) cos(2 pi k x)

Each converges to the ideal wave of timeline.signal.generators; with every harmonic below
Nyquist kept and none above it, sampling adds no alias. `aliased_fraction` is the share of a wave's
power that its harmonics at or above Nyquist carry: what a naively sampled wave folds back.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Mapping

import numpy as np
import numpy.typing as npt

HARMONIC = ("square", "saw", "triangle")
_BLOCK = 8192  # samples summed at a time, so the running sums stay in cache
# Harmonics counted at most: beyond 100,000 below Nyquist the power left above is under 1e-5
# of any of these waves (at most 8/(pi^2 K) of it), so it is counted as zero.
MAX_COUNTED = 100_000
# Samples x harmonics from which the compiled sum (timeline.signal.render_kernels: the same bits,
# ~8x faster than numpy's ~4 ns per term and sample) is used even before numba is loaded, which
# costs ~0.5 s CPU once per process. Smaller sums (8 ms at most) stay in numpy, so a render that
# only has those (every example) never loads numba.
COMPILED_WORK = 2_000_000
# Even harmonics this small against the largest are rounding (a square of duty 1/2 has ~1e-16).
ODD_ONLY = 1e-12


def harmonics_below(frequency: float, nyquist: float) -> int:
    """How many harmonics of `frequency` lie strictly below `nyquist` (K)."""
    f = abs(frequency)
    if f == 0 or nyquist / f > MAX_COUNTED:
        return MAX_COUNTED
    return max(0, math.ceil(nyquist / f) - 1)


def _duty(params: Mapping[str, float]) -> float:
    return min(1.0, max(0.0, params["duty"]))


def _harmonic_power(generator: str, params: Mapping[str, float], k: np.ndarray) -> np.ndarray:
    """Mean power of harmonic k of a unit-amplitude wave."""
    if generator == "square":
        return 8.0 * np.sin(np.pi * k * _duty(params)) ** 2 / (np.pi * k) ** 2
    if generator == "saw":
        return 2.0 / (np.pi * k) ** 2
    return np.where(k % 2 == 1, 32.0 / (np.pi**4 * k**4), 0.0)


def _mean_and_power(generator: str, params: Mapping[str, float]) -> tuple[float, float]:
    """The unit-amplitude wave's mean and its total mean power."""
    if generator == "square":
        return 2.0 * _duty(params) - 1.0, 1.0
    return 0.0, 1.0 / 3.0


def aliased_fraction(generator: str, params: Mapping[str, float], nyquist: float) -> float:
    """The share of the wave's power in harmonics at or above `nyquist` (0..1)."""
    keep = harmonics_below(params["frequency"], nyquist)
    mean, total = _mean_and_power(generator, params)
    k = np.arange(1, keep + 1, dtype=np.float64)
    kept = mean * mean + float(np.sum(_harmonic_power(generator, params, k)))
    return min(1.0, max(0.0, (total - kept) / total))


def _coefficients(
    generator: str, params: Mapping[str, float], keep: int
) -> npt.NDArray[np.complexfloating]:
    """Complex b_k (k = 1..keep) with the unit wave = mean + Re(sum_k b_k exp(2 pi i k x))."""
    k = np.arange(1, keep + 1, dtype=np.float64)
    if generator == "square":
        shift = np.exp(-2j * np.pi * k * _duty(params))
        return -1j * (2.0 / (np.pi * k)) * (1.0 - shift)
    if generator == "saw":
        return 1j * (2.0 / (np.pi * k))
    return np.where(k % 2 == 1, -8.0 / (np.pi**2 * k**2), 0.0).astype(np.complex128)


def synthesise(
    generator: str, u: np.ndarray, params: Mapping[str, float], nyquist: float
) -> np.ndarray:
    """The wave at positions u with every harmonic below `nyquist` and none at or above it."""
    keep = harmonics_below(params["frequency"], nyquist)
    mean, _ = _mean_and_power(generator, params)
    b = _coefficients(generator, params, keep)
    magnitude = np.abs(b)
    # A triangle, or a square of duty 1/2, has no even harmonics (within rounding): sum the odd
    # ones in z^2, half the terms
    odd = keep > 2 and magnitude[1::2].max() <= ODD_ONLY * magnitude.max()
    b = (b[0::2] if odd else b)[::-1]
    x = params["frequency"] * np.asarray(u, dtype=np.float64) + params["phase"] / (2.0 * np.pi)
    out = np.empty(x.shape)
    flat_x, flat_out = x.reshape(-1), out.reshape(-1)
    if flat_x.size * b.size >= COMPILED_WORK or "timeline.signal.render_kernels" in sys.modules:
        from timeline.signal.render_kernels import fourier_real

        fourier_real(flat_x, b.real.copy(), b.imag.copy(), odd, flat_out)
    else:
        _fourier_real(flat_x, b.real, b.imag, odd, flat_out)
    return params["amplitude"] * (mean + out)


def _fourier_real(
    x: np.ndarray, re: np.ndarray, im: np.ndarray, odd: bool, out: np.ndarray
) -> None:
    """out = Re(sum_k c_k z^k), z = exp(2 pi i x), c = re + i im highest k first (with `odd`,
    c lists the odd k only): Horner's rule (stable for |z| = 1) in real numpy operations, each
    rounded on its own, so the compiled loop (timeline.signal.render_kernels.fourier_real) gives the
    same bits on any machine."""
    for start in range(0, x.size, _BLOCK):
        part = x[start : start + _BLOCK]
        theta = 2.0 * np.pi * (part - np.floor(part))
        zr, zi = np.cos(theta), np.sin(theta)
        wr, wi = (zr * zr - zi * zi, zr * zi + zi * zr) if odd else (zr, zi)  # the step: z or z^2
        tr, ti = np.zeros(part.size), np.zeros(part.size)
        a, b, t = np.empty(part.size), np.empty(part.size), np.empty(part.size)
        for cr, ci in zip(re.tolist(), im.tolist(), strict=True):
            np.add(tr, cr, out=a)
            np.add(ti, ci, out=b)
            np.multiply(a, wr, out=tr)  # tr = a wr - b wi
            np.multiply(b, wi, out=t)
            np.subtract(tr, t, out=tr)
            np.multiply(a, wi, out=ti)  # ti = a wi + b wr
            np.multiply(b, wr, out=t)
            np.add(ti, t, out=ti)
        # with odd steps the sum is z times the wanted one: take Re(total * conj(z))
        out[start : start + _BLOCK] = tr * zr + ti * zi if odd else tr
