"""Compensated summation for output blocks whose terms cancel far below their own size.

The mixer adds weight * value in float64, which loses the bits of a small sum under huge
terms that cancel (10,000 clips of gains +-1e15 and one of 0.5). Where a block's terms may be
more than CANCELLING times its largest result, the mixer sums that block again here: each
product split exactly into its rounded value and its rounding error (Dekker), every part added
with Neumaier's compensation, so the error is about one rounding of the result plus
count x 2^-104 of the terms' magnitudes instead of count x 2^-52.
"""

from __future__ import annotations

import numpy as np

CANCELLING = 2.0**26  # terms' magnitudes over the largest result: where a block is summed again
_SPLIT = 134217729.0  # 2^27 + 1: Dekker's splitting constant for float64


def _split(a: np.ndarray | float) -> tuple:
    """a = high + low, each with at most 26 significant bits."""
    t = _SPLIT * a
    high = t - (t - a)
    return high, a - high


def two_product(x: np.ndarray, weight: float) -> tuple[np.ndarray, np.ndarray]:
    """(x * weight rounded, its rounding error), exact where nothing overflows (else error 0)."""
    p = x * weight
    xh, xl = _split(x)
    wh, wl = _split(weight)
    err = ((xh * wh - p) + xh * wl + xl * wh) + xl * wl
    return p, np.where(np.isfinite(err), err, 0.0)


class Compensated:
    """A running sum over a block's samples with Neumaier's compensation term."""

    def __init__(self, n: int) -> None:
        self.sum = np.zeros(n)
        self.carry = np.zeros(n)

    def add(self, a: int, z: int, x: np.ndarray, weight: float) -> None:
        """sum[a:z] += weight * x, the product's rounding error included."""
        p, err = two_product(x, weight)
        self._add(a, z, p)
        self._add(a, z, err)

    def _add(self, a: int, z: int, v: np.ndarray) -> None:
        s = self.sum[a:z]
        t = s + v
        big = np.abs(s) >= np.abs(v)
        self.carry[a:z] += np.where(big, (s - t) + v, (v - t) + s)
        self.sum[a:z] = t

    def result(self) -> np.ndarray:
        return self.sum + self.carry
