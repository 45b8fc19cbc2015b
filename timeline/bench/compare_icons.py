"""`compare` of many icons: measuring each icon once, then all pairs' distances at once.

Each size runs in a process of its own (its peak memory is its own): the icons are short tones
of varied frequency, pulse count and length, some with a stiffness or damping layer. Reported:
compare()'s wall time split into measuring the icons (rendering each once), the distance matrix
and the MDS map, and the peak RSS; and, at the smaller sizes, the pair-by-pair loop over parts()
(how distances were taken before: two percentiles per pair) for the ratio and the largest
difference between the two (float rounding).
"""

from __future__ import annotations

import argparse
import math
import os
import time
from pathlib import Path

import numpy as np

from timeline.bench.child_process import cpu_seconds, peak_rss, report, run_child
from timeline.bench.report import Table

NAME = "compare"
SUMMARY = "compare of hundreds of icons: features once, distances vectorised, peak memory"
PAIRWISE_MAX = 200  # icons up to which the old pair-by-pair loop is run beside


def icons(count: int) -> list:
    """`count` distinct icons (name, project)."""
    from timeline import edits, generator

    made = []
    for i in range(count):
        p = edits.new_project("time")
        p, drive = edits.add_track(p, "drive", "drive")
        seconds = 0.05 + 0.35 * ((i * 7) % 23) / 22
        tone = generator("sine", seconds, "tone", frequency=40.0 + (i * 37) % 260)
        p, tile = edits.add_tile(p, tone)
        for k in range(1 + i % 4):
            p, _ = edits.add_clip(p, drive, tile, k * (seconds + 0.05), gain=0.2 + 0.1 * (i % 7))
        if i % 3:
            kind = "stiffness" if i % 3 == 1 else "damping"
            p, track = edits.add_track(p, kind, kind)
            p, level = edits.add_tile(p, generator("constant", seconds, "level", value=1.0))
            p, _ = edits.add_clip(p, track, level, 0.0, gain=0.1 + 0.05 * (i % 5))
        made.append((f"icon {i}", p))
    return made


def _pairwise(measured: list) -> np.ndarray:
    """The distance matrix pair by pair, as it was taken before."""
    from timeline.similarity.distance import parts
    from timeline.similarity.features import FLOOR_DB

    floor = FLOOR_DB
    n = len(measured)
    matrix = np.zeros((n, n))
    for i in range(n):
        for j in range(i + 1, n):
            p = parts(measured[i], measured[j], floor)
            matrix[i, j] = matrix[j, i] = math.sqrt(sum(v * v for v in p.values()))
    return matrix


def child(count: int) -> None:
    """One size, measured in this process."""
    from timeline.limits.design import sample
    from timeline.similarity.compare import compare
    from timeline.similarity.distance import distances
    from timeline.similarity.features import features
    from timeline.similarity.mds import classical_mds

    made = icons(count)
    compare(made[:2])  # loads what the first render loads (numba's kernels), once per process
    before, cpu = peak_rss(), cpu_seconds()
    start = time.perf_counter()
    result = compare(made)
    wall, cpu = time.perf_counter() - start, cpu_seconds() - cpu
    peak = peak_rss()
    # the split, taken again step by step (the same work compare() does)
    start = time.perf_counter()
    measured = [features(name, sample(p, None, "normal")) for name, p in made]
    measuring = time.perf_counter() - start
    start = time.perf_counter()
    matrix, _ = distances(measured)
    matrix_s = time.perf_counter() - start
    start = time.perf_counter()
    classical_mds(matrix, 2)
    mds = time.perf_counter() - start
    row = {"wall": wall, "cpu": cpu, "measure": measuring, "matrix": matrix_s, "mds": mds}
    row |= {"peak": peak, "before": before, "pairwise": None, "difference": None}
    if count <= PAIRWISE_MAX:
        start = time.perf_counter()
        old = _pairwise(measured)
        row["pairwise"] = time.perf_counter() - start
        row["difference"] = float(np.max(np.abs(old - result.matrix)))
    report(row)


def run(quick: bool, out: Path) -> list[Table]:
    table = Table(
        "compare: wall s and CPU s (in a process of its own), split into measuring the icons, "
        "the distance matrix and the MDS map; peak RSS",
        ["icons", "compare s", "CPU s", "measure s", "matrix s", "MDS s", "pairwise matrix s",
         "max |difference| JND", "peak RSS MB", "before MB"],
    )  # fmt: skip
    for count in (50, 100) if quick else (100, 200, 400, 800):
        r = run_child(__name__, "--icons", str(count))
        table.rows.append(
            [
                count,
                f"{r['wall']:.2f}",
                f"{r['cpu']:.2f}",
                f"{r['measure']:.2f}",
                f"{r['matrix']:.3f}",
                f"{r['mds']:.3f}",
                "-" if r["pairwise"] is None else f"{r['pairwise']:.2f}",
                "-" if r["difference"] is None else f"{r['difference']:.1e}",
                f"{r['peak'] / 1e6:.0f}",
                f"{r['before'] / 1e6:.0f}",
            ]
        )
    table.notes.append(
        f"load average {' '.join(f'{x:.1f}' for x in os.getloadavg())}; target: 800 icons "
        "within 3 s (issue 19); measured after a compare of two icons in the same process (numba's "
        "kernels loaded); 'before MB' is the process with the icons built"
    )
    return [table]


if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    parser.add_argument("--icons", type=int, required=True)
    child(parser.parse_args().icons)
