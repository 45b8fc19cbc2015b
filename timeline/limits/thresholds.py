"""Perception thresholds of the hand, each with its source (docs/perception.md explains them).

* Detection of vibration (Verrillo 1963, 1966; thenar eminence, 2.9 cm^2 contactor): U-shaped
  over frequency with its minimum near 250-300 Hz, about 0.1 um peak displacement (-20 dB re
  1 um); it rises by 12 dB per octave below 250 Hz down to about 40 Hz, where the non-Pacinian
  plateau takes over, and rises again above 300 Hz (modelled at 12 dB per octave).
* Amplitude JND: 2.2-2.5 dB at 20-35 dB sensation level (Israr, Tan & Reed 2006); we take 2.2 dB,
  the lower end, so a "less than a JND" finding is one no tested hand could feel.
* Frequency discrimination: Weber fraction 0.18-0.25 (Israr, Tan & Reed 2006); we take 0.18.
* Force / torque JND: about 7 % (Jones 1989; Pang, Tan & Durlach 1991 report 5-10 %).
* Temporal resolution of touch: two taps closer than about 10 ms feel like one (Gescheider 1966,
  successive clicks on the fingertip; vibrotactile gap detection, Van Doren, Gescheider &
  Verrillo 1990, reaches a few ms only at high levels).
"""

from __future__ import annotations

import math

import numpy as np

DETECTION_MIN_DB = -20.0  # dB re 1 um peak displacement at the most sensitive frequencies
DETECTION_BEST = (250.0, 300.0)  # Hz: the bottom of the U
DETECTION_PLATEAU_HZ = 40.0  # Hz: below this the threshold stops rising (non-Pacinian plateau)
DETECTION_SLOPE_DB = 12.0  # dB per octave either side of the bottom
AMPLITUDE_JND_DB = 2.2
FREQUENCY_WEBER = 0.18
FORCE_JND = 0.07
TEMPORAL_RESOLUTION = 0.010  # s


def detection_threshold(frequency):  # noqa: ANN001, ANN201 - scalar or array in, same out
    """Peak skin displacement (m) a hand just detects at a frequency (Hz), Verrillo's U."""
    f = np.clip(np.asarray(frequency, dtype=np.float64), DETECTION_PLATEAU_HZ, None)
    low, high = DETECTION_BEST
    with np.errstate(divide="ignore"):  # both branches are computed: low / inf is 0
        octaves = np.where(f < low, np.log2(low / f), np.where(f > high, np.log2(f / high), 0.0))
    return 1e-6 * 10.0 ** ((DETECTION_MIN_DB + DETECTION_SLOPE_DB * octaves) / 20.0)


def level_difference_db(a: float, b: float) -> float:
    """|20*log10(a/b)|: how far apart two amplitudes are in dB (inf when one is zero)."""
    if a <= 0 or b <= 0:
        return 0.0 if a == b else float("inf")
    ratio = a / b
    if not 0.0 < ratio < math.inf:  # 1e-300 against 1e300: apart by more than a float holds
        return abs(20.0 * (math.log10(a) - math.log10(b)))
    return abs(20.0 * float(np.log10(ratio)))
