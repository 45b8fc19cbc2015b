"""Compiled loops (numba) for the render's hot spots, loaded on first use by large renders.

Importing numba costs a few tenths of a second of CPU, so callers import this module only when
the work is large enough to repay it; small renders keep their numpy forms, so `haptic-timeline
render` of an example never loads numba.
Each loop is written to give what its numpy form gives: the scaled add bit for bit (the product
is rounded, then added, as numpy's two passes do), the Fourier sum bit for bit (the numpy loop
of harmonic_waves rounds each real operation alike), the fractional delay of recordings bit for
bit where OpenBLAS sums np.convolve's dot products as its AVX2 kernel does (checked at first
use by timeline.signal.resample, which keeps numpy otherwise). The functions are compiled on
their first call and cached on disk (cache=True), so later processes only load them.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import cast

import numpy as np
from llvmlite import ir
from numba import njit, types
from numba.extending import intrinsic

_LANES = 128  # samples carried through the Fourier sum at a time (kept in L1 cache)
_TAPS = 64  # the fractional delay's taps (timeline.signal.resample)
_DELAY_BLOCK = 256  # outputs of the fractional delay computed side by side


@intrinsic
def _fma_intrinsic(typingctx, a, b, c):  # noqa: ARG001 (numba's signature for an intrinsic)
    """a * b + c rounded once (LLVM's fma: the instruction on x86-64 with FMA)."""
    signature = types.float64(types.float64, types.float64, types.float64)

    def codegen(context, builder, sig, args):  # noqa: ARG001
        double = ir.DoubleType()
        fn = builder.module.declare_intrinsic(
            "llvm.fma", [double], ir.FunctionType(double, [double, double, double])
        )
        return builder.call(fn, args)

    return signature, codegen


_fma = cast("Callable[[float, float, float], float]", _fma_intrinsic)  # as loops call it


@njit(cache=True)
def scaled_add(out: np.ndarray, x: np.ndarray, weight: float) -> None:
    """out += weight * x in one pass: each product rounded, then added (numpy's two roundings)."""
    for i in range(out.shape[0]):
        out[i] += weight * x[i]


_MAGNITUDE = 0x7FFFFFFFFFFFFFFF  # a float64's bits without its sign


@njit(cache=True)
def peak_bits(bits: np.ndarray) -> int:
    """The bits of np.max(np.abs(x)) for x's float64 bits viewed as int64 (non-empty): without
    the sign bit, a larger magnitude has larger bits, a nan larger than any (as numpy's max puts
    it first), so one integer maximum in one pass (vectorised) gives it exactly."""
    top = 0
    for i in range(bits.shape[0]):
        b = bits[i] & _MAGNITUDE
        top = b if b > top else top
    return top


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
        # two Horner steps per pass over the lanes: each lane's operations in the same order,
        # half the loads and stores (~20 % faster)
        count = re.shape[0]
        for k in range(0, count - 1, 2):
            cr, ci, dr, di = re[k], im[k], re[k + 1], im[k + 1]
            for j in range(m):
                xr = wr[j]
                xi = wi[j]
                a = tr[j] + cr
                b = ti[j] + ci
                r = a * xr - b * xi
                i = a * xi + b * xr
                a = r + dr
                b = i + di
                tr[j] = a * xr - b * xi
                ti[j] = a * xi + b * xr
        if count % 2:
            cr, ci = re[count - 1], im[count - 1]
            for j in range(m):
                a = tr[j] + cr
                b = ti[j] + ci
                tr[j] = a * wr[j] - b * wi[j]
                ti[j] = a * wi[j] + b * wr[j]
        for j in range(m):
            out[start + j] = tr[j] * zr[j] + ti[j] * zi[j] if odd else tr[j]


@njit(cache=True)
def fractional_delay(span: np.ndarray, taps: np.ndarray, out: np.ndarray) -> None:
    """out[i] = the dot product of span[i + 1 : i + 65] and the 64 taps, summed as numpy's
    np.convolve sums it here: OpenBLAS's ddot kernel for AVX2 (Haswell, Zen), 16 running sums
    of fused multiply-adds, lane j taking products j, j + 16, j + 32, j + 48, then added pairwise
    as its vector registers are (timeline.signal.resample checks these bits against numpy's
    before it takes this loop, and keeps numpy where they differ). ~3x numpy's speed: numpy
    calls ddot once per output."""
    n = out.shape[0]
    block = _DELAY_BLOCK
    acc = np.empty(16 * block)
    for start in range(0, n, block):
        m = min(block, n - start)
        for lane in range(16):  # a lane's four products chained in a register, 4 outputs wide
            t0, t1, t2, t3 = taps[lane], taps[lane + 16], taps[lane + 32], taps[lane + 48]
            first = start + 1 + lane
            s0 = span[first : first + m]
            s1 = span[first + 16 : first + 16 + m]
            s2 = span[first + 32 : first + 32 + m]
            s3 = span[first + 48 : first + 48 + m]
            sums = acc[lane * block : lane * block + m]
            for j in range(m):
                a = _fma(s0[j], t0, 0.0)
                a = _fma(s1[j], t1, a)
                a = _fma(s2[j], t2, a)
                sums[j] = _fma(s3[j], t3, a)
        for j in range(m):  # each 4-lane register's halves, registers 1 + 2 and 3 + 4, ...
            r0 = acc[j] + acc[2 * block + j]
            r1 = acc[block + j] + acc[3 * block + j]
            r2 = acc[4 * block + j] + acc[6 * block + j]
            r3 = acc[5 * block + j] + acc[7 * block + j]
            r4 = acc[8 * block + j] + acc[10 * block + j]
            r5 = acc[9 * block + j] + acc[11 * block + j]
            r6 = acc[12 * block + j] + acc[14 * block + j]
            r7 = acc[13 * block + j] + acc[15 * block + j]
            total = ((r0 + r2) + (r4 + r6)) + ((r1 + r3) + (r5 + r7))
            out[start + j] = 0.0 + total  # numpy's dot adds the result to 0.0
