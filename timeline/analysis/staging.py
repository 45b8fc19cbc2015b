"""Gain staging: a converted design brought within a device's limit and above what a hand feels.

A design's drive is its envelope's carrier plus each emphasis's pulse (EMPHASIS_CYCLES carrier
cycles, at most 2 / F_MIN s long), so its peak is at most the envelope's highest value, or an
emphasis's amplitude plus the envelope's highest value during its pulse (`peak`). `stage` picks
one gain for the whole design. By default (`gain_db` None, "auto") it lowers the design when its
envelope alone goes above `limit`, raises it when its peak is below `felt` (up to `felt`, at most
to `limit`), and otherwise keeps the sound's level; then each emphasis is lowered to the headroom
the envelope leaves under `limit` (the analysis ducks the envelope under an emphasis to make room
for it), so the design never asks for more than the device gives and its envelope keeps the
sound's level. A given `gain_db` is applied as it is. Either way, what was done and anything left
above the limit or below `felt` is said in `notes`.
The numbers (limit and felt level, as fractions of the drive's full scale) come from the device
and the perception thresholds (timeline.limits), which the caller looks up.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from timeline.analysis.sound import SoundAnalysis
from timeline.signal.vibration_design import EMPHASIS_CYCLES, F_MIN

PULSE = EMPHASIS_CYCLES / F_MIN  # s: the longest an emphasis pulse lasts


@dataclass(frozen=True)
class Staging:
    """Where a design's level should sit, as fractions of the drive's full scale."""

    limit: float = 1.0  # the device's largest output
    felt: float = 0.0  # the least peak a hand feels (0: not checked)
    gain_db: float | None = None  # None: auto
    target: str = "the device"  # named in the notes


@dataclass(frozen=True)
class Staged:
    """A staged analysis, the gain applied (dB) and what the user should know."""

    analysis: SoundAnalysis
    gain_db: float
    notes: tuple[str, ...]


def _under(analysis: SoundAnalysis) -> np.ndarray:
    """The envelope's highest value during each emphasis's pulse."""
    t, a = analysis.amplitude[:, 0], analysis.amplitude[:, 1]
    out = np.zeros(len(analysis.emphasis))
    for k, when in enumerate(analysis.emphasis[:, 0]):
        lo, hi = np.searchsorted(t, [when, when + PULSE], side="left")
        ends = np.interp([when, when + PULSE], t, a)
        out[k] = max(float(ends.max()), float(a[lo:hi].max()) if hi > lo else 0.0)
    return out


def peak(analysis: SoundAnalysis) -> float:
    """The most the design's drive can reach (envelope plus any emphasis pulse on it)."""
    a = analysis.amplitude[:, 1]
    top = float(a.max()) if len(a) else 0.0
    if len(analysis.emphasis):
        top = max(top, float((_under(analysis) + analysis.emphasis[:, 1]).max()))
    return top


def with_gain(analysis: SoundAnalysis, gain: float) -> SoundAnalysis:
    """The analysis with every amplitude (envelope and emphasis) times `gain`, at most 1."""
    amplitude = analysis.amplitude.copy()
    amplitude[:, 1] = np.minimum(amplitude[:, 1] * gain, 1.0)
    emphasis = analysis.emphasis.copy()
    emphasis[:, 1] = np.minimum(emphasis[:, 1] * gain, 1.0)
    return dataclasses.replace(analysis, amplitude=amplitude, emphasis=emphasis)


def _capped(analysis: SoundAnalysis, limit: float) -> tuple[SoundAnalysis, int]:
    """Each emphasis at most the headroom the envelope leaves under `limit`; how many were cut."""
    if len(analysis.emphasis) == 0:
        return analysis, 0
    room = np.maximum(limit - _under(analysis), 0.0)
    over = analysis.emphasis[:, 1] > room
    if not over.any():
        return analysis, 0
    emphasis = analysis.emphasis.copy()
    emphasis[over, 1] = room[over]
    return dataclasses.replace(analysis, emphasis=emphasis), int(over.sum())


def _db(ratio: float) -> float:
    return 20.0 * math.log10(ratio)


def stage(analysis: SoundAnalysis, staging: Staging) -> Staged:
    """The design at the level `staging` asks for (module docstring), with its notes."""
    top = peak(analysis)
    notes: list[str] = []
    if top <= 0.0:
        return Staged(analysis, 0.0, ("the sound is silent: the design has no drive",))
    envelope_top = float(analysis.amplitude[:, 1].max())
    if staging.gain_db is not None:
        gain = 10.0 ** (staging.gain_db / 20.0)
    elif envelope_top > staging.limit:
        gain = staging.limit / envelope_top
        notes.append(f"lowered {-_db(gain):.1f} dB to stay within {staging.target}'s limit")
    elif top < staging.felt:
        gain = min(staging.felt, staging.limit) / top
        notes.append(
            f"raised {_db(gain):.1f} dB: at the sound's level its peak ({top:.4f} of full "
            f"scale) is below {staging.felt:.4f}, the least a hand feels clearly "
            "(--gain 0 keeps the sound's level)"
        )
    else:
        gain = 1.0
    staged = with_gain(analysis, gain) if gain != 1.0 else analysis
    if staging.gain_db is None:
        staged, cut = _capped(staged, staging.limit)
        if cut:
            notes.append(
                f"{cut} emphasis lowered to the headroom the envelope leaves under "
                f"{staging.target}'s limit"
            )
    reached = peak(staged)
    if reached > staging.limit * (1 + 1e-9):
        notes.append(
            f"its peak ({reached:.3f} of full scale) is above {staging.target}'s limit "
            f"({staging.limit:.3f}): --gain auto, or {-_db(staging.limit / reached):.1f} dB "
            "less, keeps it within"
        )
    elif 0 < reached < staging.felt * (1 - 1e-9):
        notes.append(
            f"its peak ({reached:.4f} of full scale) is below {staging.felt:.4f}, the least a "
            f"hand feels clearly: --gain auto, or {_db(staging.felt / reached):.1f} dB more, "
            "raises it"
        )
    return Staged(staged, _db(gain), tuple(notes))
