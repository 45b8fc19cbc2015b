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
    rms: np.ndarray,
    out: np.ndarray,
    attack: float,
    release: float,
    hold: int,
    level: float,
    held: int,
) -> tuple[float, int]:
    for i in range(rms.shape[0]):
        x = rms[i]
        if x > level:
            level = attack * (level - x) + x
            held = 0
        elif held < hold:
            held += 1
        else:
            level = release * (level - x) + x
        if level < 1e-30:
            level = 0.0
        out[i] = level
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

    def process(self, block: np.ndarray) -> np.ndarray:
        """The envelope (float64) for the next samples of the sound."""
        squares = np.concatenate([self.squares, np.square(block, dtype=np.float64)])
        sums = np.cumsum(squares)
        windowed = sums[self.window :] - sums[: -self.window]
        rms = np.sqrt(np.maximum(windowed, 0.0) / self.window)
        self.squares = squares[-self.window :]
        out = np.empty_like(rms)
        self.level, self.held = _follow(
            rms, out, self.attack, self.release, self.hold, self.level, self.held
        )
        return out


def expand_tail(values: np.ndarray, threshold: float, ratio: float) -> np.ndarray:
    """Values below `threshold` fall `ratio` dB for each dB they are below it; others stay."""
    if threshold <= 0.0 or ratio == 1.0:
        return values
    below = values < threshold
    out = values.copy()
    out[below] = threshold * (values[below] / threshold) ** ratio
    return out
