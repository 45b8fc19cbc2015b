"""Every registered reader timed against its input's size, and the refusal of inputs over a limit.

Each case reads files of n, 4n and 16n units (a 16x span; `--quick` uses smaller n, the same
span). A reader's time per unit stays flat when it is linear; the fitted exponent is the slope of
log time against log size over the three sizes (least squares): 1 is linear, 2 quadratic. Times
are `read_file` (what `import` runs before placing), or `projectfile.load` for a project; best of
the runs, each after a warm-up read of a small file of the same kind. The refusal table times the
one sentence an input over each documented limit gets (docs/reliability.md, "Limits").
"""

from __future__ import annotations

import tempfile
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from timeline.bench import reader_files as files
from timeline.bench.report import Table, best_time
from timeline.errors import HapticTimelineError
from timeline.files import importing

NAME = "readers"
SUMMARY = "every reader's time against input size (exponent per reader) and its over-limit refusal"


@dataclass(frozen=True)
class Case:
    """One reader fed files of `first`, 4x and 16x `unit`s made by `make(path, n)`."""

    label: str
    ext: str
    unit: str
    first: int
    make: Callable[[Path, int], None]
    read: Callable[[Path], object] = importing.read_file


def _load_project(path: Path) -> object:
    from timeline.files import projectfile

    return projectfile.load(path)


CASES = (
    Case("AHAP overlapping continuous", ".ahap", "event", 250, files.ahap_overlapping),
    Case("AHAP one ParameterCurve", ".ahap", "point", 3_000, files.ahap_curve),
    Case("AHAP transients", ".ahap", "event", 3_000, files.ahap_transients),
    Case(".haptic emphasis", ".haptic", "breakpoint", 25_000, files.haptic_emphasis),
    Case("CSV one column", ".csv", "row", 100_000, files.csv_column),
    Case("CSV time + 2 columns", ".csv", "row", 50_000, files.csv_timed),
    Case(".mat v5", ".mat", "sample", 1_000_000, files.mat_v5),
    Case(".mat v7.3 (HDF5)", ".mat", "sample", 1_000_000, files.mat_v73),
    Case(".mat Octave text", ".mat", "sample", 100_000, files.mat_octave_text),
    Case(".npz", ".npz", "sample", 250_000, files.npz),
    Case("WAV 16-bit", ".wav", "frame", 250_000, files.sound("WAV", "PCM_16")),
    Case("AIFF 24-bit", ".aiff", "frame", 250_000, files.sound("AIFF", "PCM_24")),
    Case("FLAC 16-bit", ".flac", "frame", 250_000, files.sound("FLAC", "PCM_16")),
    Case("Ogg Vorbis", ".ogg", "frame", 100_000, files.sound("OGG", "VORBIS")),
    Case("OTIO generator clips", ".otio", "clip", 500, files.otio_clips),
    Case(".otioz generator clips", ".otioz", "clip", 500, files.otio_clips),
    Case(".hjif keyframes", ".hjif", "keyframe", 5_000, files.hjif_keyframes),
    Case(".htl project, clips", ".htl", "clip", 500, files.htl_clips, _load_project),
    Case(".htl project, samples", ".htl", "sample", 250_000, files.htl_samples, _load_project),
)


@dataclass(frozen=True)
class Refusal:
    """A file just over a documented limit, and the limit in words."""

    label: str
    ext: str
    limit: str
    make: Callable[[Path], None]
    read: Callable[[Path], object] = importing.read_file


REFUSALS = (
    Refusal(
        "AHAP, 50,001 entries (6 MB)",
        ".ahap",
        "50,000 entries and points",
        lambda p: files.ahap_transients(p, 50_001),
    ),  # fmt: skip
    Refusal(
        "AHAP, 1 curve of 50,001 points",
        ".ahap",
        "50,000 entries and points",
        lambda p: files.ahap_curve(p, 50_001),
    ),  # fmt: skip
    Refusal("AHAP over 64 MB", ".ahap", "64 MB", files.sparse(64 * 2**20 + 1)),
    Refusal(".haptic over 64 MB", ".haptic", "64 MB", files.sparse(64 * 2**20 + 1)),
    Refusal(".hjif over 64 MB", ".hjif", "64 MB", files.sparse(64 * 2**20 + 1)),
    Refusal(
        ".hjif, 500,001 keyframes",
        ".hjif",
        "500,000 keyframes",
        lambda p: files.hjif_keyframes(p, 500_001),
    ),  # fmt: skip
    Refusal("CSV over 2 GiB (sparse)", ".csv", "2 GiB", files.sparse(2**31 + 1)),
    Refusal("WAV of 2^31 + 1 frames (sparse)", ".wav", "2^31 samples", files.huge_wav),
    Refusal("FLAC declaring 2^35 frames", ".flac", "frames held", files.lying_flac),
    Refusal(".mat v5 declaring 2^31 x 2^31", ".mat", "memory of the child", files.lying_mat),
    Refusal(".otioz media over 4 GiB (declared)", ".otioz", "4 GiB unpacked", files.otioz_bomb),
    Refusal(
        ".htl over 4 GiB (sparse)", ".htl", "4 GiB", files.sparse(4 * 2**30 + 1), _load_project
    ),  # fmt: skip
)


def _slope(sizes: list[int], seconds: list[float]) -> float:
    """Least-squares slope of log time against log size."""
    return float(np.polyfit(np.log(sizes), np.log(seconds), 1)[0])


def _series(case: Case, folder: Path, quick: bool, repeat: int) -> list[list[object]]:
    first = max(1, case.first // 8) if quick else case.first
    warm = folder / f"warm{case.ext}"
    case.make(warm, max(1, first // 16))
    case.read(warm)  # the reader's modules loaded before any timing
    rows, sizes, times = [], [], []
    for n in (first, 4 * first, 16 * first):
        path = folder / f"n{n}{case.ext}"
        case.make(path, n)
        megabytes = files.size(path) / 2**20
        seconds = best_time(lambda p=path: case.read(p), repeat)
        files.remove(path)
        sizes.append(n)
        times.append(seconds)
        rows.append([case.label, f"{n:,} {case.unit}s", f"{megabytes:.2f}", f"{seconds:.3f}",
                     f"{1e6 * seconds / n:.3g}", ""])  # fmt: skip
    rows[-1][-1] = f"{_slope(sizes, times):.2f}"
    return rows


def _refusal(refusal: Refusal, folder: Path) -> list[object]:
    path = folder / f"over{refusal.ext}"
    refusal.make(path)
    said: list[str] = []

    def attempt() -> None:
        try:
            refusal.read(path)
        except HapticTimelineError as exc:
            said.append(str(exc))
        else:
            said.append("READ, NOT REFUSED")

    seconds = best_time(attempt, 1)
    files.remove(path)
    return [refusal.label, refusal.limit, f"{seconds:.3f}", said[-1][:110]]


def run(quick: bool, out: Path) -> list[Table]:
    table = Table(
        "Readers: time against input size (best of runs)",
        ["reader", "size", "file MB", "read s", "us per unit", "exponent"],
    )
    refusals = Table(
        "Readers: inputs over a documented limit", ["input", "limit", "refused in s", "sentence"]
    )
    repeat = 1 if quick else 2
    with tempfile.TemporaryDirectory() as name:
        folder = Path(name)
        for case in CASES:
            table.rows += _series(case, folder, quick, repeat)
        for refusal in REFUSALS:
            refusals.rows.append(_refusal(refusal, folder))
    table.notes.append(
        "exponent: least-squares slope of log time against log size over n, 4n, 16n "
        "(1 linear, 2 quadratic); a constant start-up cost (a child interpreter for .mat and "
        "OTIO) pulls it below 1"
    )
    return [table, refusals]
