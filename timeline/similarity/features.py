"""What a hand can tell apart in an icon, measured once per icon.

* duration (s): from the first to the last sample above silence;
* rhythm: the onsets of its events (drive between silences of at least touch's temporal
  resolution);
* envelope: the drive's RMS level in dB over 20 ms frames, on the icon's own time base;
* frequency (Hz): the energy-weighted mean of the frames' frequencies, or, below 50 Hz (a
  cycle longer than a frame), the zero-crossing rate of the whole icon;
* roughness (dB): how much the peak level jumps from one 5 ms block to the next inside events
  (blocks of 1.5 periods for carriers below 300 Hz; 0 for carriers below 50 Hz, which are felt
  as motion), which fast amplitude modulation and irregular waveforms add;
* force: the k, b, m layers over time (time icons) or the torque, damping and mass tables over
  angle (position icons), on their own axis.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from timeline.limits.design import Sampled
from timeline.limits.findings import spans
from timeline.limits.frames import FRAME, crossings, frames
from timeline.limits.thresholds import TEMPORAL_RESOLUTION

SILENT = 1e-9  # of the peak drive: below this a sample is silence
# An envelope level below this (dB re 1 N*m, or re full scale on a vibrotactile device) counts
# as nothing, whatever else is compared: 10 dB under the softest drive the default knob's held
# hand detects (0.40 mN*m peak at 40 Hz, -71 dB RMS: Verrillo's threshold through
# timeline/limits/skin.py), so a pair's distance does not depend on the rest of the set.
FLOOR_DB = -80.0
ENVELOPE_POINTS = 64  # samples of the envelope and force profiles on the icon's own axis


@dataclass(frozen=True, eq=False)
class Features:
    """The perceptual features of one icon (see the module docstring)."""

    name: str
    axis: str
    duration: float
    onsets: np.ndarray  # s from the first event's start
    envelope: np.ndarray  # dB re 1 (N*m or full scale), ENVELOPE_POINTS values
    frequency: float  # Hz (0 without drive)
    roughness: float  # dB
    force: dict[str, np.ndarray]  # term -> ENVELOPE_POINTS values (SI)
    force_scale: dict[str, float]  # term -> largest magnitude (SI)


def _resampled(values: np.ndarray) -> np.ndarray:
    if values.size == 0:
        return np.zeros(ENVELOPE_POINTS)
    x = np.linspace(0.0, values.size - 1, ENVELOPE_POINTS)
    return np.interp(x, np.arange(values.size), values)


def _events(d: np.ndarray, rate: float) -> list[tuple[int, int]]:
    """Runs of drive, joined across silences shorter than touch resolves."""
    quiet = np.abs(d) <= SILENT * max(float(np.abs(d).max(initial=0.0)), 1e-300)
    runs = spans(~quiet)
    joined: list[tuple[int, int]] = []
    for a, b in runs:
        if joined and (a - joined[-1][1] - 1) / rate < TEMPORAL_RESOLUTION:
            joined[-1] = (joined[-1][0], b)
        else:
            joined.append((a, b))
    return joined


def features(name: str, design: Sampled) -> Features:
    """Measure one icon."""
    rate = design.rate
    d = design.terms.get("d")
    if d is not None:  # beyond 1e100 an icon is as loud all the same: its squares stay finite
        d = np.clip(d, -1e100, 1e100)
    force = {t: v for t, v in design.terms.items() if t in "kbm" or design.axis == "position"}
    force_profiles = {t: _resampled(v) for t, v in force.items()}
    scales = {t: float(np.abs(v).max(initial=0.0)) for t, v in force.items()}
    # no drive, or none above 1e-300 (a full scale of 5e-324): a silent icon
    if d is None or design.axis == "position" or not (events := _events(d, rate)):
        length = design.length / rate
        return Features(name, design.axis, length, np.zeros(1), np.full(ENVELOPE_POINTS, -300.0),
                        0.0, 0.0, force_profiles, scales)  # fmt: skip
    first, last = events[0][0], events[-1][1]
    body = d[first : last + 1]
    fr = frames(body, rate)
    with np.errstate(divide="ignore"):
        level = 20.0 * np.log10(np.maximum(fr.rms, 1e-15))
    weights = fr.rms**2 * (fr.frequency > 0)
    frequency = float(np.sum(fr.frequency * weights) / np.sum(weights)) if weights.any() else 0.0
    where = crossings(body)  # over the whole icon: what 20 ms frames cannot see
    spread = where[-1] - where[0] if where.size > 1 else 0.0
    overall = (where.size - 1) * rate / (2.0 * spread) if spread > 0 else 0.0
    if overall < 1.0 / FRAME:
        frequency = overall
    fine = np.asarray(np.abs(body))
    # blocks of 5 ms, or 1.5 periods of a low carrier, so a smooth tone has a steady peak
    hop = max(1, round(max(0.005, 1.5 / frequency if frequency > 0 else 0.0) * rate))
    blocks = (
        fine[: fine.size // hop * hop].reshape(-1, hop).max(axis=1) if fine.size >= hop else fine
    )
    on = blocks > SILENT * max(float(blocks.max(initial=0.0)), 1e-300)
    with np.errstate(divide="ignore"):
        fluct = 20.0 * np.log10(blocks[on]) if on.any() else np.zeros(1)
    roughness = float(np.std(np.diff(fluct))) if fluct.size > 1 else 0.0
    if 0.0 < frequency < 1.0 / FRAME:
        roughness = 0.0  # a carrier below 50 Hz is felt as motion; the envelope has its shape
    onsets = np.array([(a - first) / rate for a, _ in events])
    return Features(name, design.axis, (last + 1 - first) / rate, onsets, _resampled(level),
                    frequency, roughness, force_profiles, scales)  # fmt: skip
