"""Breakpoints in one domain fitted in another: AHAP players interpolate sqrt(amplitude).

Core Haptics interpolates a parameter curve linearly in its own value, and the felt amplitude is
intensity squared (sharpness squared is Meta's frequency). A straight segment in one domain is a
curve in the other; the largest gap between the two, for a segment whose square roots differ by
d, is d**2 / 4 at its middle. Splitting the segment at n - 1 points evenly spaced in the square
root domain keeps that gap at d**2 / (4 n**2), so n = ceil(d / (2 sqrt(tolerance))) pieces keep
it within the tolerance, both ways.
"""

from __future__ import annotations

import math

import numpy as np

MERGE = 1e-9  # a point this close to the line through its neighbours adds nothing


def _pieces(t: np.ndarray, r: np.ndarray, tolerance: float) -> np.ndarray:
    n = np.ceil(np.abs(np.diff(r)) / (2.0 * math.sqrt(tolerance)) - 1e-12).astype(np.int64)
    return np.where(np.diff(t) > 0, np.maximum(n, 1), 1)


def _split(t: np.ndarray, n: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """For segments split into n pieces: each new point's segment and fraction along it."""
    seg = np.repeat(np.arange(len(n)), n)
    j = np.arange(len(seg)) - np.repeat(np.cumsum(n) - n, n)
    return seg, j / n[seg]


def squares_of_roots(t: np.ndarray, r: np.ndarray, tolerance: float) -> tuple[np.ndarray, ...]:
    """Values linear in the root between (t, r): squared breakpoints within tolerance of them."""
    t, r = np.asarray(t, dtype=np.float64), np.asarray(r, dtype=np.float64)
    if len(t) < 2:
        return t, r * r
    seg, s = _split(t, _pieces(t, r, tolerance))
    tt = np.append(t[seg] + (t[seg + 1] - t[seg]) * s, t[-1])
    rr = np.append(r[seg] + (r[seg + 1] - r[seg]) * s, r[-1])
    return tt, rr * rr


def roots_of_lines(t: np.ndarray, v: np.ndarray, tolerance: float) -> tuple[np.ndarray, ...]:
    """Root breakpoints whose squares, interpolated linearly in the root, stay within
    `tolerance` of the straight lines through (t, v); points on a line in the root merged."""
    t, v = np.asarray(t, dtype=np.float64), np.asarray(v, dtype=np.float64)
    r = np.sqrt(np.maximum(v, 0.0))
    if len(t) < 2:
        return t, r
    n = np.where(np.diff(v) != 0, _pieces(t, r, tolerance), 1)
    seg, s = _split(t, n)
    rr = np.where(s == 0.0, r[seg], r[seg] + (r[seg + 1] - r[seg]) * s)
    dv = v[seg + 1] - v[seg]
    frac = np.where(dv != 0, (rr * rr - v[seg]) / np.where(dv != 0, dv, 1.0), s)
    tt = np.where(s == 0.0, t[seg], t[seg] + (t[seg + 1] - t[seg]) * np.clip(frac, 0.0, 1.0))
    tt, rr = np.append(tt, t[-1]), np.append(rr, r[-1])
    return _merged(tt, rr)


def _merged(t: np.ndarray, r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Drop points that lie (within MERGE) on the line through their neighbours."""
    if len(t) < 3:
        return t, r
    t0, t1, t2 = t[:-2], t[1:-1], t[2:]
    span = t2 - t0
    line = r[:-2] + (r[2:] - r[:-2]) * (t1 - t0) / np.where(span > 0, span, 1.0)
    on_line = (span > 0) & (t1 > t0) & (t2 > t1) & (np.abs(line - r[1:-1]) <= MERGE)
    keep = np.concatenate([[True], ~on_line, [True]])
    return t[keep], r[keep]
