"""Generators above the output's Nyquist frequency: removed or band-limited, never aliased.

A closed-form shape sampled at a rate below twice its frequency aliases: a 7 kHz sine rendered
at 10 kHz comes out as a 3 kHz tone at full level. Shapes whose spectrum is known exactly
(sine, chirp, amplitude modulation, detents) are band-limited at render time: wherever their
highest frequency reaches the Nyquist frequency of the grid they are sampled on, the samples are
zero (removed, as an ideal low-pass filter would). Square, saw and triangle waves have
harmonics at every multiple of their frequency: above Nyquist their fundamental is removed the
same way; below it, when the harmonics at or above Nyquist carry more than ALIAS_LIMIT of the
wave's power, the wave is synthesised from its harmonics below Nyquist
(timeline.signal.harmonic_waves), and otherwise sampled as the ideal wave (its alias is under the
limit). Noise whose bandwidth is above Nyquist would fold its whole power into the band (20 kHz
noise at a 10 kHz rate comes out at about twice the level of its part below 5 kHz): it is
rendered as white noise up to Nyquist (one lattice value per sample) at the power the designed
noise has below Nyquist (generators.noise_level_below). timeline.rendering.aliasing names the
clips whose rendering departs audibly from their design.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from functools import lru_cache

import numpy as np

from timeline.signal.generators import noise_level_below, white_noise
from timeline.signal.harmonic_waves import HARMONIC, aliased_fraction, synthesise
from timeline.signal.vibration_design import carrier_hz

# Square/saw/triangle waves are synthesised band-limited when a naive sampling would fold back
# more than this share of their power (-30 dB); below it they are sampled as the ideal wave.
ALIAS_LIMIT = 1e-3


def _chirp_frequency(u: np.ndarray, duration: float, p: Mapping[str, float]) -> np.ndarray:
    f0, f1 = p["f0"], p["f1"]
    if p["exponential"] and f0 > 0 and f1 > 0 and f0 != f1:
        # inf (or NaN where the ratio overflows) reads as above every rate: the band limit masks it
        with np.errstate(over="ignore", invalid="ignore"):
            return f0 * np.exp(np.log(f1 / f0) * u / duration)
    return f0 + (f1 - f0) * u / duration


# Highest frequency (cycles per unit) present at position u, for shapes with a finite spectrum.
HIGHEST_FREQUENCY: dict[
    str, Callable[[np.ndarray, float, Mapping[str, float]], np.ndarray | float]
] = {
    "sine": lambda u, d, p: abs(p["frequency"]),
    "chirp": lambda u, d, p: np.abs(_chirp_frequency(u, d, p)),
    "am": lambda u, d, p: abs(p["carrier"]) + abs(p["modulation"]),
    "detents": lambda u, d, p: abs(p["count"]) / d,
    "emphasis": lambda u, d, p: carrier_hz(p["frequency"]),
}


def band_limited(
    generator: str,
    u: np.ndarray,
    nyquist: float,
    duration: float,
    params: Mapping[str, float],
    evaluate: Callable[[np.ndarray], np.ndarray],
    bounds: tuple[float, float] | None = None,
) -> np.ndarray:
    """The shape at positions u (sampled at a spacing with this Nyquist frequency) with content
    at or above Nyquist removed; `evaluate` gives the ideal shape, zero outside its span.
    `bounds`, when the caller knows them, are u's least and greatest values."""
    if generator in HARMONIC:
        if abs(params["frequency"]) >= nyquist:
            return np.zeros(np.shape(u))
        folded = _aliased_fraction(generator, params["frequency"], params.get("duty"), nyquist)
        if folded <= ALIAS_LIMIT:
            return evaluate(u)
        with np.errstate(all="ignore"):
            values = synthesise(generator, u, params, nyquist)
        if bounds is not None and bounds[0] >= 0.0 and bounds[1] <= duration:
            return values  # all of u inside the span: nothing to zero
        return np.where((u < 0) | (u > duration), 0.0, values)
    if generator == "noise" and params["bandwidth"] > nyquist:
        values = white_noise(u, params["seed"], 2.0 * nyquist, noise_level(params, nyquist))
        lo, hi = _range(u) if bounds is None else bounds
        return (
            values
            if lo >= 0.0 and hi <= duration
            else np.where((u < 0) | (u > duration), 0.0, values)
        )
    highest = HIGHEST_FREQUENCY.get(generator)
    if highest is None:
        return evaluate(u)
    # Each shape's highest frequency is constant or monotone in u (a chirp's |f0 + (f1-f0)u/d|
    # or f0 (f1/f0)^(u/d)), so its largest value over u is at the ends of u's range.
    u = np.asarray(u, dtype=np.float64)
    if u.size == 0:
        return evaluate(u)
    ends = np.array([u.min(), u.max()] if bounds is None else bounds)
    top = np.broadcast_to(highest(ends, duration, params), ends.shape)
    if top.max() < nyquist:
        return evaluate(u)  # nothing reaches Nyquist: no mask, the same values
    values = evaluate(u)
    top = np.broadcast_to(highest(u, duration, params), values.shape)
    return np.where(top < nyquist, values, 0.0)


def _range(u: np.ndarray) -> tuple[float, float]:
    """The least and greatest of u ((0, 0) when empty)."""
    return (float(np.min(u)), float(np.max(u))) if np.size(u) else (0.0, 0.0)


def noise_level(params: Mapping[str, float], nyquist: float) -> float:
    """The level of a noise band-limited to `nyquist` (its bandwidth above it): white_noise's
    factor, so its power is what the designed noise has below Nyquist."""
    return params["amplitude"] * _noise_level_below(params["bandwidth"], nyquist)


@lru_cache(maxsize=4096)
def _noise_level_below(bandwidth: float, nyquist: float) -> float:
    """noise_level_below, remembered (asked again by every render of a clip)."""
    return noise_level_below(bandwidth, nyquist)


@lru_cache(maxsize=4096)
def _aliased_fraction(generator: str, frequency: float, duty: float | None,
                      nyquist: float) -> float:  # fmt: skip
    """aliased_fraction, remembered: every render of a clip asks it again with the same values."""
    params = {"frequency": frequency} if duty is None else {"frequency": frequency, "duty": duty}
    return aliased_fraction(generator, params, nyquist)
