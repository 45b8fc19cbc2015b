"""An hour-long recording in a project file: save (what autosave does too) and load.

A float32 recording of 44.1 kHz (an imported 16-bit WAV is stored so) is made block by block,
with its content key computed as the importer does while reading, placed in a project, saved to
a temporary folder and loaded back, each step in a process of its own so its peak resident
memory is its own. Reported: wall seconds and peak RSS, as a ratio to the samples' bytes (the
process's own Python, numpy and timeline included), and the file's size.
"""

from __future__ import annotations

import argparse
import os
import tempfile
import time
from pathlib import Path

import numpy as np

from timeline.bench.child_process import cpu_seconds, peak_rss, report, run_child
from timeline.bench.report import Table

NAME = "media"
SUMMARY = "an hour-long recording in a .htl file: save and load, wall and peak memory"
RATE = 44_100.0
BLOCK = 1 << 20


def recording(seconds: float):
    """A float32 SampledTile of `seconds`, made in blocks, with its key computed as it is made."""
    from timeline.signal.samples import ContentKey
    from timeline.tiles import SampledTile

    data = np.empty(round(seconds * RATE), dtype=np.float32)
    key = ContentKey(data.dtype)
    rng = np.random.default_rng(1)
    for first in range(0, data.size, BLOCK):
        t = (first + np.arange(min(BLOCK, data.size - first))) / RATE
        wave = 0.5 * np.sin(2 * np.pi * 80 * t) + 0.05 * rng.standard_normal(t.size)
        block = data[first : first + t.size]
        block[:] = np.round(wave * 32767) / 32768  # 16-bit values: float32 exactly
        key.update(block)
    data.setflags(write=False)
    return SampledTile.from_checked(data, RATE, "recording", "recording.wav", key.key(RATE))


def child(step: str, path: Path, seconds: float) -> None:
    """One step (save or load), measured in this process."""
    from timeline import edits
    from timeline.files import projectfile

    if step == "save":
        project, _ = edits.add_tile(edits.new_project(), recording(seconds))
        before, cpu = peak_rss(), cpu_seconds()
        start = time.perf_counter()
        projectfile.save(project, path)
    else:
        before, cpu = peak_rss(), cpu_seconds()
        start = time.perf_counter()
        projectfile.load(path)
    wall, cpu = time.perf_counter() - start, cpu_seconds() - cpu
    report({"wall": wall, "cpu": cpu, "peak": peak_rss(), "before": before})


def run(quick: bool, out: Path) -> list[Table]:
    seconds = 60.0 if quick else 3600.0
    samples = round(seconds * RATE) * 4
    table = Table(
        f"A {seconds / 60:g}-minute float32 recording at 44.1 kHz ({samples / 1e6:.0f} MB of "
        "samples) saved and loaded, each in a process of its own",
        ["step", "wall s", "CPU s", "peak RSS MB", "peak / samples", "RSS before MB", "file MB"],
    )
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "hour.htl"
        for step in ("save", "load"):
            r = run_child(__name__, step, str(path), str(seconds))
            table.rows.append(
                [
                    step,
                    f"{r['wall']:.2f}",
                    f"{r['cpu']:.2f}",
                    f"{r['peak'] / 1e6:.0f}",
                    f"{r['peak'] / samples:.2f}",
                    f"{r['before'] / 1e6:.0f}",
                    f"{path.stat().st_size / 1e6:.0f}",
                ]
            )
    table.notes.append(
        f"load average {' '.join(f'{x:.1f}' for x in os.getloadavg())}; targets (issue 19): "
        "save and load within 2 s each, peak within 1.5x the samples; save includes the fsync; "
        "load hashes the samples (blake2b) on a second thread while it reads; CPU counts every "
        "thread of the process"
    )
    return [table]


if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    parser.add_argument("step", choices=("save", "load"))
    parser.add_argument("path", type=Path)
    parser.add_argument("seconds", type=float)
    args = parser.parse_args()
    child(args.step, args.path, args.seconds)
