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
def fourier_real(x: np.ndarray, re: np.ndarray, im: np.ndarray, out: np.ndarray) -> None:
    """out = Re(sum_k c_k z^k) for z = exp(2 pi i x), c listed highest k first (re, im), by
    Horner's rule on z (stable for |z| = 1): the loop of harmonic_waves.synthesise, compiled."""
    n = x.shape[0]
    tr = np.empty(_LANES)
    ti = np.empty(_LANES)
    zr = np.empty(_LANES)
    zi = np.empty(_LANES)
    for start in range(0, n, _LANES):
        m = min(_LANES, n - start)
        for j in range(m):
            v = x[start + j]
            theta = 2.0 * math.pi * (v - math.floor(v))
            zr[j] = math.cos(theta)
            zi[j] = math.sin(theta)
            tr[j] = 0.0
            ti[j] = 0.0
        for k in range(re.shape[0]):
            cr = re[k]
            ci = im[k]
            for j in range(m):
                a = tr[j] + cr
                b = ti[j] + ci
                tr[j] = a * zr[j] - b * zi[j]
                ti[j] = a * zi[j] + b * zr[j]
        for j in range(m):
            out[start + j] = tr[j]
