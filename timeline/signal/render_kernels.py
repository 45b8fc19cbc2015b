"""Compiled loops (numba) for the render's hot spots, loaded on first use by large renders.

Importing numba costs a few tenths of a second of CPU, so callers import this module only when
the work is large enough to repay it; small renders keep their numpy forms, so `haptic-timeline
render` of an example never loads numba.
Each loop is written to give what its numpy form gives: the scaled add bit for bit (the product
is rounded, then added, as numpy's two passes do), the Fourier sum within a few ulps (numpy's
complex multiply may fuse a multiply-add, the loop does not). The functions are compiled on
their first call and cached on disk (cache=True), so later processes only load them.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

_LANES = 256  # samples carried through the Fourier sum at a time (kept in L1 cache)


@njit(cache=True)
def scaled_add(out: np.ndarray, x: np.ndarray, weight: float) -> None:
    """out += weight * x in one pass: each product rounded, then added (numpy's two roundings)."""
    for i in range(out.shape[0]):
        out[i] += weight * x[i]


@njit(cache=True)
def fourier_real(x: np.ndarray, re: np.ndarray, im: np.ndarray, odd: bool, out: np.ndarray) -> None:
    """out = Re(sum_k c_k z^k) for z = exp(2 pi i x), c listed highest k first (re, im; with
    `odd`, the odd k only, summed in z^2), by Horner's rule (stable for |z| = 1): the numpy loop
    of harmonic_waves._fourier_real, compiled, operation for operation."""
    n = x.shape[0]
    tr = np.empty(_LANES)
    ti = np.empty(_LANES)
    zr = np.empty(_LANES)
    zi = np.empty(_LANES)
    wr = np.empty(_LANES)
    wi = np.empty(_LANES)
    for start in range(0, n, _LANES):
        m = min(_LANES, n - start)
        for j in range(m):
            v = x[start + j]
            theta = 2.0 * math.pi * (v - math.floor(v))
            zr[j] = math.cos(theta)
            zi[j] = math.sin(theta)
            if odd:
                wr[j] = zr[j] * zr[j] - zi[j] * zi[j]
                wi[j] = zr[j] * zi[j] + zi[j] * zr[j]
            else:
                wr[j] = zr[j]
                wi[j] = zi[j]
            tr[j] = 0.0
            ti[j] = 0.0
        for k in range(re.shape[0]):
            cr = re[k]
            ci = im[k]
            for j in range(m):
                a = tr[j] + cr
                b = ti[j] + ci
                tr[j] = a * wr[j] - b * wi[j]
                ti[j] = a * wi[j] + b * wr[j]
        for j in range(m):
            out[start + j] = tr[j] * zr[j] + ti[j] * zi[j] if odd else tr[j]
