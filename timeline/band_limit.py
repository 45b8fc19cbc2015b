"""Generators above the output's Nyquist frequency: removed where the shape allows, named where not.

A closed-form shape sampled at a rate below twice its frequency aliases: a 7 kHz sine rendered
at 10 kHz comes out as a 3 kHz tone at full level. Shapes whose spectrum is known exactly
(sine, chirp, amplitude modulation, detents) are band-limited at render time: wherever their
highest frequency reaches the Nyquist frequency of the grid they are sampled on, the samples are
zero (removed, as an ideal low-pass filter would). Square, saw and triangle waves have
harmonics at every multiple of their frequency: above Nyquist their fundamental is removed the
same way; below it their upper harmonics still alias, and `aliasing_notes` names those clips.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping

import numpy as np

_HARMONIC = ("square", "saw", "triangle")


def _chirp_frequency(u: np.ndarray, duration: float, p: Mapping[str, float]) -> np.ndarray:
    f0, f1 = p["f0"], p["f1"]
    if p["exponential"] and f0 > 0 and f1 > 0 and f0 != f1:
        return f0 * np.exp(np.log(f1 / f0) * u / duration)
    return f0 + (f1 - f0) * u / duration


# Highest frequency (cycles per unit) present at position u, for shapes with a finite spectrum.
_HIGHEST: dict[str, Callable[[np.ndarray, float, Mapping[str, float]], np.ndarray | float]] = {
    "sine": lambda u, d, p: abs(p["frequency"]),
    "chirp": lambda u, d, p: np.abs(_chirp_frequency(u, d, p)),
    "am": lambda u, d, p: abs(p["carrier"]) + abs(p["modulation"]),
    "detents": lambda u, d, p: abs(p["count"]) / d,
}


def band_limited(
    generator: str, values: np.ndarray, u0: float, du: float, duration: float, params: Mapping
) -> np.ndarray:
    """values (the shape on the grid u0 + k*du) with content at or above Nyquist removed."""
    if du == 0:
        return values
    nyquist = 0.5 / abs(du)
    if generator in _HARMONIC:
        return values if abs(params["frequency"]) < nyquist else np.zeros_like(values)
    highest = _HIGHEST.get(generator)
    if highest is None:
        return values
    u = u0 + du * np.arange(values.size)
    top = np.broadcast_to(highest(u, duration, params), values.shape)
    return np.where(top < nyquist, values, 0.0)


def aliasing_notes(project, rate: float | None = None) -> list[str]:
    """One sentence per generator clip that renders differently from its design at `rate`.

    Names clips whose content is removed above Nyquist, and square/saw/triangle clips whose
    harmonics alias (the third harmonic, at 1/3 or 1/9 of the level, is above Nyquist).
    """
    from timeline.tiles import GeneratorTile

    rate = float(project.rate if rate is None else rate)
    nyquist = 0.5 * rate
    unit = "Hz" if project.axis == "time" else "cycles/rad"
    notes = []
    for track in project.tracks:
        for clip in track.clips:
            tile = project.tiles.get(clip.tile_id)
            if not isinstance(tile, GeneratorTile):
                continue
            params = dict(tile.params)
            speed = clip.stretch if clip.stretch_mode == "squeeze" else 1.0
            where = f"clip {clip.id} ({tile.name}) on track {track.name!r}"
            if tile.generator in _HARMONIC:
                f = abs(params["frequency"]) / speed
                if f >= nyquist:
                    notes.append(
                        f"{where} at {f:g} {unit} is above the {nyquist:g} {unit} Nyquist "
                        "frequency of this rate and was removed"
                    )
                elif 3 * f >= nyquist:
                    notes.append(
                        f"{where}: the harmonics of its {f:g} {unit} {tile.generator} wave above "
                        f"{nyquist:g} {unit} alias at this rate; render at a higher rate or use "
                        "a sine"
                    )
                continue
            highest = _HIGHEST.get(tile.generator)
            if highest is None:
                continue
            u = np.linspace(clip.source_in, clip.source_out, 257)
            top = np.max(np.broadcast_to(highest(u, tile.duration, params), u.shape)) / speed
            if top >= nyquist:
                notes.append(
                    f"{where} reaches {top:g} {unit}, above the {nyquist:g} {unit} Nyquist "
                    "frequency of this rate: that part was removed"
                )
    return notes
