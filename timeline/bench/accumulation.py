"""Accumulation at the extremes: long renders at 192 kHz in chunks (peak memory), and 10,000
overlapping clips with amplitudes from 1e-12 to 1e12, against math.fsum references.

The long render runs in a child process so its peak resident memory (ru_maxrss) is its own:
three overlapping clips (gains 1e-12, 1 and 1e12) over the whole range, rendered with
render_chunks by a mixer with 64 MiB caches. Memory is bounded by the caches and the chunk size,
not by the length: libraries (~55 MiB) + 2 x 64 MiB of caches + the temporaries of evaluating
three clips over one chunk (~10 chunk buffers), under MEMORY_BOUND for any length.
"""

from __future__ import annotations

import json
import math
import resource
import subprocess
import sys
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from timeline import edits
from timeline.bench.report import Table
from timeline.model import Clip, Project
from timeline.rendering.mixer import Mixer
from timeline.tiles import generator

NAME = "accumulation"
SUMMARY = "hour at 192 kHz in chunks (peak RSS) and 10,000 overlapping clips vs fsum"
RATE = 192_000.0
CACHE = 64 * 2**20
CHUNK = 10.0  # s per chunk
LONG = ((1e-12, 0.01), (1.0, 3.0), (1e12, 97.0))  # (gain, sine frequency Hz)
FULL_SCALE = 0.18  # N*m, the drive track's full scale
MEMORY_BOUND = 400 * 2**20  # bytes of peak RSS for these settings, whatever the length


def long_project(seconds: float) -> Project:
    """Three overlapping sine clips spanning the whole range, gains 1e-12, 1 and 1e12."""
    project = edits.new_project(templates=False)
    project, track = edits.add_track(project, "drive")
    for gain, freq in LONG:
        project, tile = edits.add_tile(project, generator("sine", seconds, frequency=freq))
        project, _ = edits.add_clip(project, track, tile, 0.0, gain=gain)
    return project


def long_reference(t: float) -> tuple[float, float]:
    """The exact sum at time t (math.fsum) and the sum of the terms' magnitudes."""
    terms = [FULL_SCALE * g * math.sin(2 * math.pi * f * t) for g, f in LONG]
    return math.fsum(terms), math.fsum(abs(x) for x in terms)


def child(seconds: float) -> dict:
    """Render the long project in chunks; report errors at sampled points and peak RSS."""
    project = long_project(seconds)
    mixer = Mixer(cache_bytes=CACHE)
    worst, samples, start = 0.0, 0, time.perf_counter()
    for t0, layers in mixer.render_chunks(project, 0.0, seconds, RATE, chunk=CHUNK):
        out = layers["drive"]
        for i in range(0, len(out), 1_000_003):
            ref, scale = long_reference(t0 + i / RATE)
            worst = max(worst, abs(float(out[i]) - ref) / (scale or 1.0))
        samples += len(out)
    elapsed = time.perf_counter() - start
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
    return dict(samples=samples, worst=worst, seconds=elapsed, rss=rss)


def overlapping(count: int = 10_000) -> tuple[float, int]:
    """Worst error of `count` overlapping 0.2 s sines at 192 kHz relative to the magnitudes."""
    rng = np.random.default_rng(5)
    project = edits.new_project(templates=False)
    project, track = edits.add_track(project, "drive")
    sines = []
    for f in range(1, 21):
        project, tile = edits.add_tile(project, generator("sine", 0.2, frequency=f * 5.0))
        sines.append((tile, f * 5.0))
    starts = np.round(rng.uniform(0, 0.1, count) * RATE) / RATE
    gains = rng.uniform(-1, 1, count) * 10.0 ** rng.uniform(-12, 12, count)
    clips, spec = [], []
    for i, (s, g) in enumerate(zip(starts.tolist(), gains.tolist(), strict=True)):
        tile, f = sines[i % 20]
        clips.append(Clip(f"x{i}", tile, s, 0.0, 0.2, gain=g))
        spec.append((s, g, f))
    project = replace(project, tracks=(replace(project.track(track), clips=tuple(clips)),))
    out = Mixer().render(project, 0.0, 0.3, RATE)["drive"]
    worst = 0.0
    for i in range(0, len(out), 4_801):
        t = i / RATE
        terms = [FULL_SCALE * g * math.sin(2 * math.pi * f * (t - s))
                 for s, g, f in spec if s <= t < s + 0.2]  # fmt: skip
        scale = math.fsum(abs(x) for x in terms) or 1.0
        worst = max(worst, abs(float(out[i]) - math.fsum(terms)) / scale)
    return worst, len(out)


def run(quick: bool, out: Path) -> list[Table]:
    seconds = 120.0 if quick else 3600.0
    result = subprocess.run(
        [sys.executable, "-m", "timeline.bench.accumulation", str(seconds)],
        capture_output=True, text=True, check=True,
    )  # fmt: skip
    long = json.loads(result.stdout)
    worst, n = overlapping()
    chunk_bytes = CHUNK * RATE * 8
    table = Table(
        "Accumulation against math.fsum (errors relative to the sum of the terms' magnitudes)",
        ["case", "samples", "worst relative error", "render s", "peak RSS MiB"],
    )
    case = f"{seconds / 60:g} min at 192 kHz in {CHUNK:g} s chunks, gains 1e-12..1e12"
    rss = long["rss"] / 2**20
    table.rows.append([case, long["samples"], long["worst"], long["seconds"], rss])
    table.rows.append(
        ["10,000 overlapping clips at 192 kHz, gains 1e-12..1e12", n, worst, "-", "-"]
    )
    within = long["rss"] <= MEMORY_BOUND
    table.notes += [
        "error bound stated (tests/stability): relative error <= 1e-12 of the sum of magnitudes",
        f"memory bound stated: libraries + 2 x {CACHE / 2**20:g} MiB caches + ~10 chunk buffers "
        f"of {chunk_bytes / 2**20:.1f} MiB, under {MEMORY_BOUND / 2**20:g} MiB for any length: "
        f"{'within' if within else 'NOT within'} (peak RSS of the child process)",
    ]
    return [table]


if __name__ == "__main__":
    print(json.dumps(child(float(sys.argv[1]))))
