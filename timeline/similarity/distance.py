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
  on its own time base, floored at FLOOR_DB = -80 dB re 1 N*m or full scale, a fixed level
  under the detection threshold, so a pair's distance is the same in any set) / 2.2 dB
  (amplitude JND, Israr, Tan & Reed 2006): a change to one event of five counts in full, a few
  points of edges do not;
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
        present = a.force.get(term, b.force.get(term))  # one of the two has the layer
        pa = a.force.get(term, np.zeros_like(present))
        pb = b.force.get(term, np.zeros_like(present))
        scale = max(a.force_scale.get(term, 0.0), b.force_scale.get(term, 0.0))
        if scale > 0:
            total += (_spread(pa - pb) / scale / FORCE_JND) ** 2
    return math.sqrt(total)


def parts(a: Features, b: Features, floor: float = FLOOR_DB) -> dict[str, float]:
    """Each feature's difference between two icons, in JNDs: the formula for one pair, which
    distances() takes for all pairs at once."""
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


class Parts:
    """Each pair's per-feature parts, read as parts[i][j] -> {feature: JNDs} ({} on the diagonal),
    made on demand from one n x n matrix per feature (DIMENSIONS)."""

    def __init__(self, matrices: dict[str, np.ndarray]) -> None:
        self.matrices = matrices

    def __len__(self) -> int:
        return len(next(iter(self.matrices.values())))

    def __getitem__(self, i: int) -> _PartsRow:
        return _PartsRow(self, i)


class _PartsRow:
    def __init__(self, parts: Parts, i: int) -> None:
        self.parts, self.i = parts, i

    def __getitem__(self, j: int) -> dict[str, float]:
        if j == self.i:
            return {}
        return {name: float(m[self.i, j]) for name, m in self.parts.matrices.items()}


PAIRS_AT_ONCE = 1 << 15  # pairs whose profile differences are taken together (bounded memory)


def _pairwise_log_ratio(values: np.ndarray, weber: float) -> np.ndarray:
    """_log_ratio of every pair of values, all at once."""
    a, b = values[:, None], values[None, :]
    positive = (a > 0) & (b > 0)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.abs(np.log(np.where(positive, a, 1.0) / np.where(positive, b, 1.0)))
    return np.where(positive, ratio / math.log(1.0 + weber), np.where(a == b, 0.0, 1.0 / weber))


def _pairwise_rhythm(onsets: list[np.ndarray]) -> np.ndarray:
    """_rhythm of every pair: interval k of both icons taken for all pairs at once."""
    counts = np.array([o.size for o in onsets])
    intervals = np.zeros((len(onsets), max(int(counts.max()) - 1, 0)))
    for i, o in enumerate(onsets):
        intervals[i, : max(o.size - 1, 0)] = np.diff(o)
    shared = np.minimum(counts[:, None], counts[None, :]) - 1  # intervals both icons have
    squares = np.zeros((len(onsets), len(onsets)))
    for k in range(intervals.shape[1]):
        term = _pairwise_log_ratio(intervals[:, k], DURATION_WEBER)
        squares += np.where(k < shared, term * term, 0.0)
    missing = RHYTHM_EVENT * np.abs(counts[:, None] - counts[None, :])
    return np.hypot(missing, np.sqrt(squares))


def _percentile_of_rows(values: np.ndarray) -> np.ndarray:
    """np.percentile(values, PERCENTILE, axis=-1) with its linear interpolation, from one sort of
    the rows (numpy's vectorised sort takes a sixth of the time of the partition it uses)."""
    last = values.shape[-1] - 1
    index = PERCENTILE / 100.0 * last
    below = math.floor(index)
    t = index - below
    ordered = np.sort(values, axis=-1)
    a, b = ordered[..., below], ordered[..., min(below + 1, last)]
    step = b - a
    return a + step * t if t < 0.5 else b - step * (1.0 - t)  # numpy's lerp, either side


def _pairwise_spread(profiles: np.ndarray, pairs: tuple[np.ndarray, np.ndarray]) -> np.ndarray:
    """_spread of the difference of the profiles (rows) of each pair (i, j), for the pairs
    given (i < j), a block of pairs at a time; the symmetric matrix, 0 for the pairs not given."""
    n = len(profiles)
    out = np.zeros((n, n))
    rows, cols = pairs
    for first in range(0, rows.size, PAIRS_AT_ONCE):
        i, j = rows[first : first + PAIRS_AT_ONCE], cols[first : first + PAIRS_AT_ONCE]
        out[i, j] = out[j, i] = _percentile_of_rows(np.abs(profiles[i] - profiles[j]))
    return out


def _pairwise_force(icons: list[Features], pairs: tuple[np.ndarray, np.ndarray]) -> np.ndarray:
    """_force of every pair: per term, the pairs where either icon has it (the other takes a
    zero profile)."""
    squares = np.zeros((len(icons), len(icons)))
    for term in sorted({t for f in icons for t in f.force}):
        size = next(f.force[term].size for f in icons if term in f.force)
        profiles = np.array([f.force.get(term, np.zeros(size)) for f in icons])
        scale = np.array([f.force_scale.get(term, 0.0) for f in icons])
        larger = np.maximum(scale[:, None], scale[None, :])
        felt = larger[pairs] > 0
        spread = _pairwise_spread(profiles, (pairs[0][felt], pairs[1][felt]))
        with np.errstate(divide="ignore", invalid="ignore"):
            squares += np.where(larger > 0, (spread / larger / FORCE_JND) ** 2, 0.0)
    return np.sqrt(squares)


def _check_one_axis(icons: list[Features]) -> None:
    """The error parts() gives for the first pair of icons on different axes."""
    other = next((b for b in icons[1:] if b.axis != icons[0].axis), None)
    if other is not None:
        parts(icons[0], other)  # raises the sentence naming the two


def distances(icons: list[Features]) -> tuple[np.ndarray, Parts]:
    """The symmetric distance matrix (JNDs) and each pair's per-feature parts: the numbers
    parts() gives pair by pair (to float rounding), with each feature taken for all pairs at
    once and the percentiles of a block of pairs from one sort."""
    _check_one_axis(icons)
    floor = FLOOR_DB
    roughness = np.array([f.roughness for f in icons])
    pairs = np.triu_indices(len(icons), 1)
    envelopes = np.maximum(np.array([f.envelope for f in icons]), floor)
    matrices = {
        "duration": _pairwise_log_ratio(np.array([f.duration for f in icons]), DURATION_WEBER),
        "rhythm": _pairwise_rhythm([f.onsets for f in icons]),
        "envelope": _pairwise_spread(envelopes, pairs) / AMPLITUDE_JND_DB,
        "frequency": _pairwise_log_ratio(np.array([f.frequency for f in icons]), FREQUENCY_WEBER),
        "roughness": np.abs(roughness[:, None] - roughness[None, :]) / AMPLITUDE_JND_DB,
        "force": _pairwise_force(icons, pairs),
    }
    total = sum(m * m for m in matrices.values())
    matrix = np.sqrt(total)
    np.fill_diagonal(matrix, 0.0)
    for m in matrices.values():
        np.fill_diagonal(m, 0.0)
    return matrix, Parts(matrices)
