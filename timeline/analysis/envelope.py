"""The amplitude envelope: a short moving RMS followed by an attack/hold/release follower.

The follower moves exponentially towards its input, reaching 99 % of a rise within `attack`
seconds and 99 % of a fall within `release` seconds; after any rise it holds its level for `hold`
seconds before it starts to fall, so short gaps in a sound do not chop the vibration. The loop
runs per sample and carries its state between blocks, so a long sound is analysed in pieces.

`expand_tail` then lets the envelope fall faster once it is far below the sound's peak (a
downward expander, docs/convert.md "Tails"): designers cut the tails a hand hardly feels.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numba import njit


def _coefficient(seconds: float, rate: float) -> float:
    """Per-sample smoothing factor that covers 99 % of a step in `seconds` (0: immediate)."""
    samples = seconds * rate
    return 0.0 if samples <= 0 else float(0.01 ** (1.0 / samples))


@njit(cache=True)
def _follow(
    block: np.ndarray,
    squares: np.ndarray,
    out: np.ndarray,
    attack: float,
    release: float,
    hold: int,
    level: float,
    held: int,
) -> tuple[float, int]:
    """The moving RMS of `block` over len(squares) samples (`squares`: the squares before it,
    updated in place) fed to the follower, in one pass; returns the follower's state."""
    w, n = squares.shape[0], block.shape[0]
    # running sums of the squares from the window's history on; the ring holds the last w, so
    # ring[i % w] is the sum before the window that ends at sample i
    ring = np.empty(w)
    total = 0.0
    for j in range(w):
        total += squares[j]
        ring[j] = total
    for i in range(n):
        x = np.float64(block[i])
        before = ring[i % w]
        total += x * x
        ring[i % w] = total
        rms = np.sqrt(max(total - before, 0.0) / w)
        if rms > level:
            level = attack * (level - rms) + rms
            held = 0
        elif held < hold:
            held += 1
        else:
            level = release * (level - rms) + rms
        if level < 1e-30:
            level = 0.0
        out[i] = level
    keep = min(w, n)
    squares[: w - keep] = squares[keep:]
    for j in range(keep):
        x = np.float64(block[n - keep + j])
        squares[w - keep + j] = x * x
    return level, held


@dataclass
class EnvelopeFollower:
    """Windowed RMS and follower state carried from block to block."""

    rate: float
    window: int
    attack: float
    release: float
    hold: int
    squares: np.ndarray  # the last `window` squared samples (the RMS window's history)
    level: float = 0.0
    held: int = 0

    @classmethod
    def create(
        cls, rate: float, rms_window: float, attack: float, hold: float, release: float
    ) -> EnvelopeFollower:
        window = max(1, int(rms_window * rate))
        return cls(
            rate,
            window,
            _coefficient(attack, rate),
            _coefficient(release, rate),
            int(hold * rate),
            np.zeros(window),
        )

    def process(self, block: np.ndarray, out: np.ndarray | None = None) -> np.ndarray:
        """The envelope (float64) for the next samples of the sound, written into `out` (as many
        float64 as the block) when given."""
        out = np.empty(len(block)) if out is None else out[: len(block)]
        self.level, self.held = _follow(
            np.ascontiguousarray(block), self.squares, out, self.attack, self.release,
            self.hold, self.level, self.held,
        )  # fmt: skip
        return out


def expand_tail(values: np.ndarray, threshold: float, ratio: float) -> np.ndarray:
    """Values below `threshold` fall `ratio` dB for each dB they are below it; others stay."""
    if threshold <= 0.0 or ratio == 1.0:
        return values
    below = values < threshold
    out = values.copy()
    out[below] = threshold * (values[below] / threshold) ** ratio
    return out
