"""`convert` of long WAV files: peak memory against the file's size.

A 16-bit mono WAV at 44.1 kHz (an 80 Hz tone under a slow envelope, with noise) is written to a
temporary folder, then converted in a process of its own (its peak resident memory is its own):
two hours to .haptic (the design only: the sound is read in blocks, twice) and one hour to .htl
(the project also keeps the sound: its mono mix read block by block into the float32 array the
tile keeps, 2 bytes of file becoming 4 in memory). The peak includes the process's Python,
numpy, numba and LLVM (the analysis' compiled kernels). A conversion of a 2 s sound runs first in
a process of its own, so the kernels are compiled and cached on disk as after a user's first run.
A second table gives each step's resident memory as it ends and the peak so far.
"""

from __future__ import annotations

import argparse
import os
import tempfile
import time
from pathlib import Path

import numpy as np

from timeline.bench.child_process import peak_rss, process_status, report, run_child
from timeline.bench.report import Table

NAME = "convert-memory"
SUMMARY = "convert of a 2-hour WAV (.haptic) and a 1-hour one (.htl): peak memory vs file size"
RATE = 44_100
FULL = ((7200.0, ".haptic"), (3600.0, ".htl"))  # seconds of sound, output
QUICK = ((120.0, ".haptic"), (60.0, ".htl"))
WARM_UP = 2.0  # seconds of the sound converted first (numba's kernels compiled and cached)
STAGES = ("analysed", "placed", "written")  # what convert_file's `stages` hears


def write_wav(path: Path, seconds: float) -> None:
    """A 16-bit mono WAV of `seconds`, written in blocks."""
    import soundfile as sf

    rng = np.random.default_rng(1)
    total = int(seconds * RATE)
    with sf.SoundFile(path, "w", RATE, 1, subtype="PCM_16") as f:
        for first in range(0, total, 1 << 20):
            t = (first + np.arange(min(1 << 20, total - first))) / RATE
            wave = 0.5 * np.sin(2 * np.pi * 80 * t) * (0.5 + 0.5 * np.sin(2 * np.pi * 0.05 * t))
            f.write(wave + 0.05 * rng.standard_normal(t.size))


def resident() -> float:
    """Resident memory of this process now, in bytes (VmRSS; 0 where there is no /proc)."""
    return process_status("VmRSS") or 0.0


def child(sound: Path, output: Path) -> None:
    """Convert, measured in this process (after its imports), step by step."""
    from timeline.files.convert import convert_file

    before = peak_rss()
    stages = {"imported": (resident(), before)}
    start = time.perf_counter()
    convert_file(
        sound, output, stages=lambda stage: stages.update({stage: (resident(), peak_rss())})
    )
    wall = time.perf_counter() - start
    report({"wall": wall, "peak": peak_rss(), "before": before, "stages": stages})


def run(quick: bool, out: Path) -> list[Table]:
    table = Table(
        "convert of a 16-bit mono WAV at 44.1 kHz, in a process of its own",
        ["sound", "to", "file MB", "wall s", "peak RSS MB", "peak / file", "RSS before MB"],
    )
    steps = Table(
        "convert step by step: resident memory as each step ends, and the peak so far",
        ["sound", "to", "step", "RSS MB", "peak so far MB", "peak / file"],
    )
    cases = QUICK if quick else FULL
    with tempfile.TemporaryDirectory() as folder:
        warm = Path(folder) / "warm.wav"
        write_wav(warm, WARM_UP)
        for suffix in {suffix for _, suffix in cases}:
            run_child(__name__, str(warm), str(Path(folder) / f"warm{suffix}"))
        for seconds, suffix in cases:
            sound = Path(folder) / f"sound{seconds:g}.wav"
            write_wav(sound, seconds)
            size = sound.stat().st_size
            r = run_child(__name__, str(sound), str(Path(folder) / f"out{suffix}"))
            table.rows.append(
                [
                    f"{seconds / 60:g} min",
                    suffix,
                    f"{size / 1e6:.0f}",
                    f"{r['wall']:.1f}",
                    f"{r['peak'] / 1e6:.0f}",
                    f"{r['peak'] / size:.2f}",
                    f"{r['before'] / 1e6:.0f}",
                ]
            )
            for stage in ("imported", *STAGES):
                rss, peak = r["stages"][stage]
                steps.rows.append(
                    [
                        f"{seconds / 60:g} min",
                        suffix,
                        stage,
                        f"{rss / 1e6:.0f}",
                        f"{peak / 1e6:.0f}",
                        f"{peak / size:.2f}",
                    ]
                )
            sound.unlink()
    table.notes.append(
        f"load average {' '.join(f'{x:.1f}' for x in os.getloadavg())}; target (issue 19): "
        "converting to .haptic peaks well under the file's size"
    )
    return [table, steps]


if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    parser.add_argument("sound", type=Path)
    parser.add_argument("output", type=Path)
    args = parser.parse_args()
    child(args.sound, args.output)
