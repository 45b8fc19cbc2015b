"""Cubic curves through control points: natural cubic spline and PCHIP, evaluated with numpy.

The same curves scipy's CubicSpline(bc_type="natural") and PchipInterpolator make (within
rounding: tests/core/test_splines.py holds them to 1e-11 of the value range), built once per tile
and evaluated by one searchsorted and a Horner step per sample, so a render neither imports
scipy.interpolate (a second of start-up) nor pays its per-call overhead on every clip.
"""

from __future__ import annotations

import numpy as np

# Evaluate piece by piece (not by a search per sample) when the grid has this many samples per
# piece of the curve: below it the per-piece numpy calls cost more than the per-sample gathers.
SAMPLES_PER_PIECE = 512


class PiecewiseCubic:
    """y = ((d*s + c)*s + b)*s + a with s = u - x[i] on [x[i], x[i+1]]; u inside [x0, xn]."""

    def __init__(self, x: np.ndarray, a: np.ndarray, b: np.ndarray, c: np.ndarray,
                 d: np.ndarray) -> None:  # fmt: skip
        self.x, self.a, self.b, self.c, self.d = x, a, b, c, d

    def __call__(self, u: np.ndarray, monotone: bool = False) -> np.ndarray:
        """The curve at u; `monotone` tells that u is sorted either way (a render's grid), which
        otherwise a pass over u finds out."""
        u = np.asarray(u, dtype=np.float64)
        if u.ndim == 1 and u.size >= SAMPLES_PER_PIECE * (len(self.x) - 1) and u.size > 1:
            if monotone:
                up, down = u[0] <= u[-1], u[0] > u[-1]
            else:
                with np.errstate(invalid="ignore"):
                    steps = np.diff(u)
                up, down = (steps >= 0).all(), (steps <= 0).all()
            if up:
                return self._sorted(u)
            if down:
                return self._sorted(u[::-1])[::-1]
        i = np.clip(np.searchsorted(self.x, u, side="right") - 1, 0, len(self.x) - 2)
        s = u - self.x[i]
        return ((self.d[i] * s + self.c[i]) * s + self.b[i]) * s + self.a[i]

    def _sorted(self, u: np.ndarray) -> np.ndarray:
        """The curve at ascending u, one piece at a time with its coefficients as scalars: the
        same operations on each sample as the gathering form (the same bits), without the
        per-sample search and gathers (a clip's grid spans few pieces with many samples each)."""
        x = self.x
        edges = [0, *np.searchsorted(u, x[1:-1], side="left").tolist(), u.size]
        out = np.empty(u.size)
        for i, (lo, hi) in enumerate(zip(edges[:-1], edges[1:], strict=True)):
            if hi > lo:
                s = u[lo:hi] - x[i]
                out[lo:hi] = ((self.d[i] * s + self.c[i]) * s + self.b[i]) * s + self.a[i]
        return out


def natural_cubic(x: np.ndarray, y: np.ndarray) -> PiecewiseCubic:
    """The natural cubic spline (zero curvature at both ends) through at least 3 points."""
    x, y = np.asarray(x, dtype=np.float64), np.asarray(y, dtype=np.float64)
    h = np.diff(x)
    slope = np.diff(y) / h
    n = len(x)
    # Second derivatives m[1..n-2] from h[i-1] m[i-1] + 2 (h[i-1] + h[i]) m[i] + h[i] m[i+1]
    # = 6 (slope[i] - slope[i-1]), m[0] = m[n-1] = 0: a tridiagonal system (Thomas algorithm).
    m = np.zeros(n)
    diag = 2.0 * (h[:-1] + h[1:])
    rhs = 6.0 * np.diff(slope)
    upper = h[1:-1]
    lower = h[1:-1]
    diag, rhs = diag.copy(), rhs.copy()
    for k in range(1, n - 2):
        w = lower[k - 1] / diag[k - 1]
        diag[k] -= w * upper[k - 1]
        rhs[k] -= w * rhs[k - 1]
    inner = np.zeros(n - 2)
    inner[-1] = rhs[-1] / diag[-1]
    for k in range(n - 4, -1, -1):
        inner[k] = (rhs[k] - upper[k] * inner[k + 1]) / diag[k]
    m[1:-1] = inner
    b = slope - h * (2.0 * m[:-1] + m[1:]) / 6.0
    return PiecewiseCubic(x, y[:-1], b, m[:-1] / 2.0, np.diff(m) / (6.0 * h))


def pchip(x: np.ndarray, y: np.ndarray) -> PiecewiseCubic:
    """The monotone piecewise cubic Hermite curve (Fritsch-Carlson slopes) through >= 3 points."""
    x, y = np.asarray(x, dtype=np.float64), np.asarray(y, dtype=np.float64)
    h = np.diff(x)
    slope = np.diff(y) / h
    d = np.zeros(len(x))
    w1 = 2.0 * h[1:] + h[:-1]
    w2 = h[1:] + 2.0 * h[:-1]
    same_sign = np.sign(slope[1:]) * np.sign(slope[:-1]) > 0
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):  # 1/inf is a 0 slope
        mean = (w1 / slope[:-1] + w2 / slope[1:]) / (w1 + w2)
        d[1:-1] = np.where(same_sign, 1.0 / mean, 0.0)
    d[0] = _pchip_end(h[0], h[1], slope[0], slope[1])
    d[-1] = _pchip_end(h[-1], h[-2], slope[-1], slope[-2])
    c = (3.0 * slope - 2.0 * d[:-1] - d[1:]) / h
    cubic = (d[:-1] + d[1:] - 2.0 * slope) / h**2
    return PiecewiseCubic(x, y[:-1], d[:-1], c, cubic)


def _pchip_end(h0: float, h1: float, m0: float, m1: float) -> float:
    """One-sided three-point slope at an end, kept monotone (shape-preserving)."""
    d = ((2.0 * h0 + h1) * m0 - h0 * m1) / (h0 + h1)
    if np.sign(d) != np.sign(m0):
        return 0.0
    if np.sign(m0) != np.sign(m1) and abs(d) > abs(3.0 * m0):
        return 3.0 * m0
    return float(d)
