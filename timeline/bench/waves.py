"""What band-limiting square, saw and triangle waves costs, against sampling the ideal wave.

Each wave is rendered for 10 s at 10 kHz (`normal`) both ways, best of `repeat` runs in this
process; the ratio is band-limited time over ideal-wave time. The cases are the worst (a saw
just above the alias limit, the most harmonics summed), typical ones, and one under the limit.
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np

from timeline.bench.report import Table
from timeline.signal.harmonic_waves import aliased_fraction, harmonics_below
from timeline.signal.render_presets import preset
from timeline.tiles import generator

NAME = "waves"
SUMMARY = "band-limited square/saw/triangle synthesis: cost against the ideal wave"
RATE = 10_000.0
CASES = (("saw", 8.3), ("square", 12.5), ("square", 100.0), ("square", 2000.0),
         ("triangle", 1100.0), ("square", 6.5))  # fmt: skip


def _best(fn, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return min(times)


def run(quick: bool, out: Path) -> list[Table]:
    seconds, repeat = (2.0, 3) if quick else (10.0, 5)
    n = int(seconds * RATE)
    grid = np.arange(n) / RATE
    table = Table(
        f"Square, saw and triangle waves, {seconds:g} s at {RATE:g} Hz",
        [
            "wave",
            "Hz",
            "harmonics kept",
            "alias power",
            "band-limited ms",
            "ideal ms",
            "ratio",
            "ms per rendered s",
        ],  # fmt: skip
        notes=[
            "alias power: share of the wave's power at or above Nyquist; above 1e-3 the wave"
            " is band-limited, under it the ideal wave is sampled"
        ],  # fmt: skip
    )
    for name, frequency in CASES:
        tile = generator(name, seconds, frequency=frequency)
        limited = _best(lambda t=tile: t.render(0.0, 1 / RATE, n, preset("normal")), repeat)
        ideal = _best(lambda t=tile: t.evaluate(grid), repeat)
        table.rows.append([
            name, frequency, harmonics_below(frequency, RATE / 2),
            aliased_fraction(name, dict(tile.params), RATE / 2), 1e3 * limited, 1e3 * ideal,
            limited / ideal, 1e3 * limited / seconds,
        ])  # fmt: skip
    return [table]
