"""Reader time against input size: .haptic (one emphasis per breakpoint), CSV and .mat.

Each reader reads files of n, 2n and 4n entries; a near-linear reader's time doubles with each
(the "x per doubling" column stays near 2). The .haptic files are the hostile kind of issue 25:
every breakpoint carries an emphasis of its own, so none is shared. Times are `read_file` (what
`import` runs before placing), best of the runs.
"""

from __future__ import annotations

import json
import tempfile
from collections.abc import Callable
from pathlib import Path

import numpy as np

from timeline.bench.report import Table, best_time
from timeline.files import importing

NAME = "readers"
SUMMARY = "reader time against input size (.haptic emphasis, CSV rows, .mat samples)"
SIZES = {".haptic": 50_000, ".csv": 500_000, ".mat": 2_000_000}  # the smallest of each series


def haptic_file(path: Path, n: int) -> None:
    """n amplitude breakpoints 1 ms apart, each with an emphasis of its own."""
    rng = np.random.default_rng(25)
    levels = np.round(rng.uniform(0.0, 1.0, (n, 3)), 6).tolist()
    amplitude = [
        {"time": i / 1000, "amplitude": a, "emphasis": {"amplitude": e, "frequency": f}}
        for i, (a, e, f) in enumerate(levels)
    ]
    doc = {"version": {"major": 1, "minor": 0, "patch": 0},
           "signals": {"continuous": {"envelopes": {"amplitude": amplitude}}}}  # fmt: skip
    path.write_text(json.dumps(doc))


def csv_file(path: Path, n: int) -> None:
    """n values of one column at a rate given in a comment."""
    values = np.random.default_rng(25).uniform(-1.0, 1.0, n)
    path.write_text("# rate=10000\n" + "\n".join(f"{v:.17g}" for v in values) + "\n")


def mat_file(path: Path, n: int) -> None:
    """One variable of n samples and its rate."""
    import scipy.io

    values = np.random.default_rng(25).uniform(-1.0, 1.0, n)
    scipy.io.savemat(path, {"drive": values, "fs": 10_000.0}, oned_as="column")


WRITERS: dict[str, Callable[[Path, int], None]] = {
    ".haptic": haptic_file,
    ".csv": csv_file,
    ".mat": mat_file,
}


def run(quick: bool, out: Path) -> list[Table]:
    table = Table(
        "Readers: time against input size (best of runs)",
        ["format", "entries", "file MB", "read s", "x per doubling"],
    )
    repeat = 1 if quick else 3
    with tempfile.TemporaryDirectory() as folder:
        for ext, first in SIZES.items():
            first = first // 10 if quick else first
            previous = None
            warm = Path(folder) / f"warm{ext}"
            WRITERS[ext](warm, 100)
            importing.read_file(warm)  # the reader's modules loaded before any timing
            for n in (first, 2 * first, 4 * first):
                path = Path(folder) / f"n{n}{ext}"
                WRITERS[ext](path, n)
                seconds = best_time(lambda p=path: importing.read_file(p), repeat)
                growth = "" if previous is None else f"{seconds / previous:.2f}"
                table.rows.append([ext, f"{n:,}", f"{path.stat().st_size / 2**20:.1f}",
                                   f"{seconds:.3f}", growth])  # fmt: skip
                previous = seconds
                path.unlink()
    table.notes.append("near-linear: 'x per doubling' near 2 (1 s per 2x input stays 2 s)")
    return [table]
