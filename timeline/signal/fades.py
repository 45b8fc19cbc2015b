"""Fade curves: gain from 0 to 1 over x in [0, 1] for each fade shape."""

from __future__ import annotations

import numpy as np

_EXPONENTIAL_RANGE = 1000.0  # a 60 dB exponential curve, offset so it starts at exactly 0


def fade_in_gain(x: np.ndarray, shape: str) -> np.ndarray:
    """Gain of a fade-in at fraction x of its length (clipped to [0, 1])."""
    x = np.clip(x, 0.0, 1.0)
    if shape == "linear":
        return x
    if shape == "equal-power":
        return np.sin(0.5 * np.pi * x)
    if shape == "exponential":
        return (_EXPONENTIAL_RANGE**x - 1.0) / (_EXPONENTIAL_RANGE - 1.0)
    if shape == "s-curve":
        return 0.5 - 0.5 * np.cos(np.pi * x)
    raise ValueError(f"unknown fade shape {shape!r}")


def fade_envelope(pos: np.ndarray, duration: float, fade_in, fade_out) -> np.ndarray | None:
    """Product of a clip's fade-in and fade-out gains at offsets pos, or None if no fades."""
    env = None
    # a denormal fade's fraction overflows to inf: clipped to 1, past the fade, as it should be
    with np.errstate(over="ignore"):
        if fade_in.length > 0:
            env = fade_in_gain(pos / fade_in.length, fade_in.shape)
        if fade_out.length > 0:
            out = fade_in_gain((duration - pos) / fade_out.length, fade_out.shape)
            env = out if env is None else env * out
    return env
