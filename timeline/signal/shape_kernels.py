"""Compiled per-kind loops (numba) for a clip's shape on a render grid, fused into one pass.

Each loop builds the grid u = u0 + du*i itself, evaluates the shape, zeroes it outside the tile
and writes the result once, where the numpy forms (timeline.signal.generators, splines, fades)
make a temporary array per operation: sine, chirp, detents, AM, noise, ADSR, splines and fades. A
sine, chirp or detent series is one libm sin per sample either way (1.00-1.03x on a warm
clip); in a render, where each clip's temporaries are fresh memory, its loop saves allocating
and first touching them. Every loop performs the numpy
form's operations in its order, each rounded on its own (numba neither reorders nor fuses a
multiply-add without fastmath), and calls the same libm functions numpy calls for float64 (sin,
cos, pow, expm1), so it gives numpy's bits: tests/core/test_shape_kernels.py holds each to
np.array_equal against its numpy form. Loaded only where timeline.signal.compiled allows it.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

TWO_PI = 2.0 * np.pi
_GOLDEN = np.uint64(0x9E3779B97F4A7C15)
_MIX1 = np.uint64(0xBF58476D1CE4E5B9)
_MIX2 = np.uint64(0x94D049BB133111EB)


@njit(cache=True)
def _grid(u0: float, du: float, i: int) -> float:
    """The render grid's position i: (float(i) * du) + u0, as timeline.tiles builds it."""
    return float(i) * du + u0


@njit(cache=True)
def am(u0: float, du: float, out: np.ndarray, duration: float, omega_c: float, omega_m: float,
       depth: float, norm: float, amplitude: float) -> None:  # fmt: skip
    """amplitude * ((1 + depth sin(omega_m u)) / norm) * sin(omega_c u), norm = 1 + |depth|."""
    for i in range(out.shape[0]):
        u = _grid(u0, du, i)
        if u < 0.0 or u > duration:
            out[i] = 0.0
        else:
            envelope = (1.0 + depth * math.sin(omega_m * u)) / norm
            out[i] = amplitude * envelope * math.sin(omega_c * u)


@njit(cache=True)
def sine(u0: float, du: float, out: np.ndarray, duration: float, omega: float, phase: float,
         amplitude: float) -> None:  # fmt: skip
    """generators._sine: amplitude * sin(omega u + phase), omega = 2 pi frequency."""
    for i in range(out.shape[0]):
        u = _grid(u0, du, i)
        if u < 0.0 or u > duration:
            out[i] = 0.0
        else:
            out[i] = amplitude * math.sin(omega * u + phase)


@njit(cache=True)
def chirp(u0: float, du: float, out: np.ndarray, duration: float, f0: float, half_span: float,
          amplitude: float) -> None:  # fmt: skip
    """generators._chirp, linear: amplitude * sin(2 pi (f0 u + half_span u u / duration)),
    half_span = 0.5 (f1 - f0)."""
    for i in range(out.shape[0]):
        u = _grid(u0, du, i)
        if u < 0.0 or u > duration:
            out[i] = 0.0
        else:
            out[i] = amplitude * math.sin(TWO_PI * (f0 * u + half_span * u * u / duration))


@njit(cache=True)
def exponential_chirp(u0: float, du: float, out: np.ndarray, duration: float, scale: float,
                      rate: float, amplitude: float) -> None:  # fmt: skip
    """generators._chirp, exponential (f0 != f1): amplitude * sin(scale expm1(rate u) / rate),
    scale = 2 pi f0."""
    for i in range(out.shape[0]):
        u = _grid(u0, du, i)
        if u < 0.0 or u > duration:
            out[i] = 0.0
        else:
            out[i] = amplitude * math.sin(scale * math.expm1(rate * u) / rate)


@njit(cache=True)
def detents(u0: float, du: float, out: np.ndarray, duration: float, shift: float, period: float,
            negated: float) -> None:  # fmt: skip
    """generators._detents: negated * sin(2 pi (u - shift) / period), shift = phase * period,
    negated = -amplitude."""
    for i in range(out.shape[0]):
        u = _grid(u0, du, i)
        if u < 0.0 or u > duration:
            out[i] = 0.0
        else:
            out[i] = negated * math.sin(TWO_PI * (u - shift) / period)


@njit(cache=True)
def adsr(u0: float, du: float, out: np.ndarray, duration: float, attack: float, decay: float,
         sustain: float, release: float) -> None:  # fmt: skip
    """generators._adsr: each sample takes the last of its phases that applies (attack, decay,
    release over sustain), as the numpy form's masked assignments do one after another."""
    decayed = attack + decay
    release_start = duration - release
    drop = 1.0 - sustain
    for i in range(out.shape[0]):
        u = _grid(u0, du, i)
        v = sustain
        if attack > 0.0 and u < attack:
            v = u / attack
        if decay > 0.0 and u >= attack and u < decayed:
            v = 1.0 - drop * (u - attack) / decay
        if release > 0.0 and u >= release_start:
            x = (duration - u) / release
            x = x if x > 0.0 else 0.0  # np.clip's order, as _fade_gain
            x = x if x < 1.0 else 1.0
            v = sustain * x
        out[i] = 0.0 if u < 0.0 or u > duration else v


@njit(cache=True)
def _hash_unit(index: np.int64, seed: np.uint64) -> float:
    """generators._hash_unit for one index: splitmix64 to a uniform value in [-1, 1)."""
    z = np.uint64(index) * _GOLDEN + seed
    z = (z ^ (z >> np.uint64(30))) * _MIX1
    z = (z ^ (z >> np.uint64(27))) * _MIX2
    z = z ^ (z >> np.uint64(31))
    return float(z >> np.uint64(11)) * (2.0 / 2.0**53) - 1.0


@njit(cache=True)
def value_noise(u0: float, du: float, out: np.ndarray, duration: float, lattice: float,
                seed: np.uint64, amplitude: float) -> None:  # fmt: skip
    """generators._noise: lattice values every 1/lattice joined by a smooth step (the caller
    keeps |u * lattice| below 2**62, where the float-to-integer conversion is exact)."""
    for i in range(out.shape[0]):
        u = _grid(u0, du, i)
        if u < 0.0 or u > duration:
            out[i] = 0.0
            continue
        x = u * lattice
        k = math.floor(x)
        f = x - k
        w = f * f * (3.0 - 2.0 * f)
        index = np.int64(k)
        a = _hash_unit(index, seed)
        b = _hash_unit(index + np.int64(1), seed)
        out[i] = amplitude * (a + (b - a) * w)


@njit(cache=True)
def white_noise(u0: float, du: float, out: np.ndarray, duration: float, lattice: float,
                seed: np.uint64, level: float) -> None:  # fmt: skip
    """generators.white_noise: one lattice value per sample, the nearest to u * lattice."""
    for i in range(out.shape[0]):
        u = _grid(u0, du, i)
        if u < 0.0 or u > duration:
            out[i] = 0.0
        else:
            out[i] = level * _hash_unit(np.int64(math.floor(u * lattice + 0.5)), seed)


@njit(cache=True)
def spline(u0: float, du: float, out: np.ndarray, duration: float, x: np.ndarray, a: np.ndarray,
           b: np.ndarray, c: np.ndarray, d: np.ndarray, first_v: float,
           last_v: float) -> None:  # fmt: skip
    """SplineTile's values: the piecewise cubic at u clipped to [x0, xn], the end values at and
    beyond the ends, zero outside [0, duration]. The piece of u is the last x[p] <= u (the first
    piece below x0, the last from x[n-2] on), found by walking from the previous sample's."""
    first, last = x[0], x[x.shape[0] - 1]
    top = x.shape[0] - 2
    p = 0
    for i in range(out.shape[0]):
        u = _grid(u0, du, i)
        if u < 0.0 or u > duration:
            out[i] = 0.0
        elif u >= last:
            out[i] = last_v
        elif u <= first:
            out[i] = first_v
        else:
            while p < top and u >= x[p + 1]:
                p += 1
            while p > 0 and u < x[p]:
                p -= 1
            s = u - x[p]
            out[i] = ((d[p] * s + c[p]) * s + b[p]) * s + a[p]


@njit(cache=True)
def _fade_gain(x: float, shape: int) -> float:
    """fades.fade_in_gain of one x: 0 linear, 1 equal-power, 2 exponential, 3 s-curve."""
    x = x if x > 0.0 else 0.0  # np.clip's order: the bound unless x is beyond it (-0.0 -> 0.0)
    x = x if x < 1.0 else 1.0
    if shape == 0:
        return x
    if shape == 1:
        return math.sin(0.5 * np.pi * x)
    if shape == 2:
        return (1000.0**x - 1.0) / (1000.0 - 1.0)
    return 0.5 - 0.5 * math.cos(np.pi * x)


@njit(cache=True)
def fade(values: np.ndarray, lo: int, hi: int, pos0: float, rate: float, duration: float,
         in_length: float, in_shape: int, out_length: float, out_shape: int) -> None:  # fmt: skip
    """values[lo:hi] *= the fades' gain at pos0 + k/rate (a length of 0: no such fade)."""
    for k in range(lo, hi):
        pos = float(k) / rate + pos0
        if in_length > 0.0:
            gain = _fade_gain(pos / in_length, in_shape)
            if out_length > 0.0:
                gain = gain * _fade_gain((duration - pos) / out_length, out_shape)
        else:
            gain = _fade_gain((duration - pos) / out_length, out_shape)
        values[k] *= gain
