"""A perceptual distance between icons, in just-noticeable differences (JNDs).

Each feature's difference is divided by the smallest difference a hand notices on it, so 1.0
means "just noticeable" on that feature; the features combine as a Euclidean distance (the
assumption behind MDS maps of haptic icons, MacLean & Enriquez 2003). Two icons closer than
ALIKE are listed as too alike to be told apart reliably.

* duration: |ln(Da/Db)| / ln(1 + 0.16) (vibrotactile duration Weber fraction about 0.16:
  Jones, Poliakoff & Wells 2009, 160 ms at a 1 s standard);
* rhythm: the onsets matched in order, |ln| of each inter-onset interval ratio / ln(1.16), plus
  RHYTHM_EVENT JNDs for each event one icon has and the other lacks;
* envelope: the 90th percentile of the point-by-point |difference| of the two dB envelopes (each
  on its own time base, floored 60 dB below the loudest icon) / 2.2 dB (amplitude JND, Israr,
  Tan & Reed 2006): a change to one event of five counts in full, a few points of edges do not;
* frequency: |ln(fa/fb)| / ln(1 + 0.18) (Weber fraction 0.18, same source);
* roughness: |difference| / 2.2 dB (it is a level fluctuation);
* force: per layer, the 90th percentile of the |difference| of the two profiles relative to the
  larger's peak, / 0.07 (force JND, Jones 1989); layers add as squares.
"""

from __future__ import annotations

import math

import numpy as np

from timeline.errors import HapticTimelineError
from timeline.limits.thresholds import AMPLITUDE_JND_DB, FORCE_JND, FREQUENCY_WEBER
from timeline.similarity.features import FLOOR_DB, Features

DURATION_WEBER = 0.16
RHYTHM_EVENT = 2.0  # JNDs for an event one icon has and the other lacks
ALIKE = 1.0  # JNDs: closer than this, two icons are too alike
PERCENTILE = 90.0  # of a profile's point-by-point differences
DIMENSIONS = ("duration", "rhythm", "envelope", "frequency", "roughness", "force")


def _log_ratio(a: float, b: float, weber: float) -> float:
    if a <= 0 or b <= 0:
        return 0.0 if a == b else 1.0 / weber  # present against absent: clearly different
    return abs(math.log(a / b)) / math.log(1.0 + weber)


def _rhythm(a: np.ndarray, b: np.ndarray) -> float:
    n = min(a.size, b.size)
    missing = RHYTHM_EVENT * abs(a.size - b.size)
    ia, ib = np.diff(a[:n]), np.diff(b[:n])
    parts = [_log_ratio(float(x), float(y), DURATION_WEBER) for x, y in zip(ia, ib, strict=True)]
    return math.hypot(missing, math.hypot(*parts) if parts else 0.0)


def _spread(difference: np.ndarray) -> float:
    """The PERCENTILE-th percentile of |difference|: one changed event counts, a few points of
    misaligned edges do not."""
    return float(np.percentile(np.abs(difference), PERCENTILE))


def _envelope(a: np.ndarray, b: np.ndarray, floor: float) -> float:
    return _spread(np.maximum(a, floor) - np.maximum(b, floor)) / AMPLITUDE_JND_DB


def _force(a: Features, b: Features) -> float:
    total = 0.0
    for term in set(a.force) | set(b.force):
        pa = a.force.get(term, np.zeros_like(next(iter(b.force.values()))))
        pb = b.force.get(term, np.zeros_like(pa))
        scale = max(a.force_scale.get(term, 0.0), b.force_scale.get(term, 0.0))
        if scale > 0:
            total += (_spread(pa - pb) / scale / FORCE_JND) ** 2
    return math.sqrt(total)


def parts(a: Features, b: Features, floor: float = -300.0) -> dict[str, float]:
    """Each feature's difference between two icons, in JNDs."""
    if a.axis != b.axis:
        raise HapticTimelineError(
            f"{a.name} is a {a.axis} icon and {b.name} a {b.axis} one: compare icons of one axis"
        )
    return {
        "duration": _log_ratio(a.duration, b.duration, DURATION_WEBER),
        "rhythm": _rhythm(a.onsets, b.onsets),
        "envelope": _envelope(a.envelope, b.envelope, floor),
        "frequency": _log_ratio(a.frequency, b.frequency, FREQUENCY_WEBER),
        "roughness": abs(a.roughness - b.roughness) / AMPLITUDE_JND_DB,
        "force": _force(a, b),
    }


def distances(icons: list[Features]) -> tuple[np.ndarray, list[list[dict[str, float]]]]:
    """The symmetric distance matrix (JNDs) and each pair's per-feature parts."""
    loudest = max((float(f.envelope.max()) for f in icons), default=0.0)
    floor = loudest + FLOOR_DB
    n = len(icons)
    matrix = np.zeros((n, n))
    table: list[list[dict[str, float]]] = [[{} for _ in icons] for _ in icons]
    for i in range(n):
        for j in range(i + 1, n):
            p = parts(icons[i], icons[j], floor)
            matrix[i, j] = matrix[j, i] = math.sqrt(sum(v * v for v in p.values()))
            table[i][j] = table[j][i] = p
    return matrix, table
