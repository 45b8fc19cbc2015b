"""A shape's samples on a render grid by its compiled loop (timeline.signal.shape_kernels), where
one applies: the same bits as the numpy forms, in one pass.

The loops are used where timeline.signal.compiled allows (numba loaded, or a grid large enough
to repay loading it); smaller renders (every example) keep numpy. Each function returns None
where its loop does not apply (a shape reaching Nyquist, which numpy masks per sample; a spline
of one or two points), and the caller takes the numpy form.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from timeline.signal import compiled
from timeline.signal.band_limit import HIGHEST_FREQUENCY, noise_level
from timeline.signal.generators import TWO_PI

_INDEX_LIMIT = 2.0**62  # |u * lattice| below this converts to int64 exactly
_KINDS = ("sine", "chirp", "detents", "am", "noise", "adsr")  # generators with a loop


def _ends(u0: float, du: float, n: int) -> tuple[float, float]:
    """The grid's least and greatest u (its first and last: a grid is monotone)."""
    first, last = u0, float(np.float64(n - 1) * du + u0)
    return min(first, last), max(first, last)


def generator_on_grid(generator: str, params: Mapping[str, float], duration: float, u0: float,
                      du: float, n: int, nyquist: float) -> np.ndarray | None:  # fmt: skip
    """The generator at u0 + du*i (i < n), band-limited to `nyquist` and zero outside
    [0, duration], as GeneratorTile.render gives it without decimation; or None."""
    if generator not in _KINDS or n <= 0 or not compiled.compiled_wanted(n):
        return None
    lo, hi = _ends(u0, du, n)
    highest = HIGHEST_FREQUENCY.get(generator)
    if highest is not None:
        top = highest(np.array([lo, hi]), duration, params)  # a number, or one per end
        if (top if isinstance(top, float) else float(np.max(top))) >= nyquist:
            return None  # masked per sample by band_limited
    from timeline.signal import shape_kernels as k

    out = np.empty(n)
    p = params
    if generator == "noise":
        return _noise(k, p, duration, u0, du, out, nyquist, max(-lo, hi))
    if generator == "sine":
        k.sine(u0, du, out, duration, TWO_PI * p["frequency"], p["phase"], p["amplitude"])
    elif generator == "chirp":
        if not _chirp(k, p, duration, u0, du, out):
            return None
    elif generator == "adsr":
        k.adsr(u0, du, out, duration, p["attack"], p["decay"], p["sustain"], p["release"])
    elif generator == "detents":
        period = duration / p["count"]
        k.detents(u0, du, out, duration, p["phase"] * period, period, -p["amplitude"])
    else:
        k.am(u0, du, out, duration, TWO_PI * p["carrier"], TWO_PI * p["modulation"], p["depth"],
             1.0 + abs(p["depth"]), p["amplitude"])  # fmt: skip
    return out


def _chirp(k, p: Mapping[str, float], duration: float, u0: float, du: float,
           out: np.ndarray) -> bool:  # fmt: skip
    """A chirp's loop, with the numpy form's constants (generators._chirp) worked out as it
    works them out; False for an exponential chirp of one frequency (numpy's sin(2 pi f0 u)
    keeps a -0.0 that the sine loop's + 0.0 phase would turn to +0.0)."""
    f0, f1 = p["f0"], p["f1"]
    if not p["exponential"]:
        k.chirp(u0, du, out, duration, f0, 0.5 * (f1 - f0), p["amplitude"])
    elif f0 != f1:
        rate = float(np.log(f1 / f0) / duration)
        k.exponential_chirp(u0, du, out, duration, TWO_PI * f0, rate, p["amplitude"])
    else:
        return False
    return True


def _noise(k, p: Mapping[str, float], duration: float, u0: float, du: float, out: np.ndarray,
           nyquist: float, reach: float) -> np.ndarray | None:  # fmt: skip
    """Value noise, or white noise at its level below Nyquist when its bandwidth is above."""
    seed = np.uint64(int(p["seed"]) & 0xFFFFFFFFFFFFFFFF)
    if p["bandwidth"] > nyquist:
        lattice = 2.0 * nyquist
        if min(reach, duration) * lattice + 1.0 >= _INDEX_LIMIT:
            return None
        k.white_noise(u0, du, out, duration, lattice, seed, noise_level(p, nyquist))
        return out
    lattice = 2.0 * p["bandwidth"]
    if min(reach, duration) * lattice + 1.0 >= _INDEX_LIMIT:
        return None
    k.value_noise(u0, du, out, duration, lattice, seed, p["amplitude"])
    return out


def spline_on_grid(x: np.ndarray, a: np.ndarray, b: np.ndarray, c: np.ndarray, d: np.ndarray,
                   end_values: tuple[float, float], duration: float, u0: float, du: float,
                   n: int) -> np.ndarray | None:  # fmt: skip
    """A spline tile's piecewise cubic (knots x, pieces a..d) at u0 + du*i, as SplineTile gives
    it; or None."""
    if n <= 0 or not compiled.compiled_wanted(n):
        return None
    from timeline.signal import shape_kernels as k

    out = np.empty(n)
    k.spline(u0, du, out, duration, x, a, b, c, d, end_values[0], end_values[1])
    return out


_FADE_SHAPES = {"linear": 0, "equal-power": 1, "exponential": 2, "s-curve": 3}


def fade_on_grid(values: np.ndarray, lo: int, hi: int, pos0: float, rate: float,
                 duration: float, fade_in: tuple[float, str] | None,
                 fade_out: tuple[float, str] | None) -> bool:  # fmt: skip
    """values[lo:hi] *= the fades' gains at clip offsets pos0 + k/rate ((length, shape) each, or
    None), as fades.fade_envelope gives them; False (nothing done) where no loop applies."""
    if not compiled.compiled_wanted(len(values)) or (fade_in is None and fade_out is None):
        return False
    from timeline.signal import shape_kernels as k

    in_length, in_shape = fade_in if fade_in is not None else (0.0, "linear")
    out_length, out_shape = fade_out if fade_out is not None else (0.0, "linear")
    k.fade(values, lo, hi, pos0, rate, duration, in_length, _FADE_SHAPES[in_shape], out_length,
           _FADE_SHAPES[out_shape])  # fmt: skip
    return True
