"""Simulated knob speed: a 10 s icon with varying coefficients at 10 kHz, as a multiple of real
time, and as a ratio to a bare Python loop of the same length measured in this process; and the
first block's cost in a new process (compiling the numba loop, or loading it from numba's cache)."""

from __future__ import annotations

import math
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from device.sim import KnobPhysics
from timeline.bench.report import Table, figure, save
from timeline.plugins.device_protocol import CoefficientBlock, Hand

NAME = "sim-speed"
SUMMARY = "simulated knob speed as a multiple of real time (10 s icon at 10 kHz)"
RATE = 10_000.0
TARGET = 300.0  # x real time (docs/performance.md)
FIRST_BLOCK = """
import time
import numpy as np
from device.sim import KnobPhysics
from timeline.plugins.device_protocol import CoefficientBlock
knob = KnobPhysics()
block = CoefficientBlock(np.zeros(1000), np.zeros(1000), np.zeros(1000))
start = time.perf_counter()
knob.run_block(block)
print(time.perf_counter() - start)
"""


def icon(seconds: float, mass: bool) -> list[CoefficientBlock]:
    """A varying icon in 0.1 s blocks: a 5 Hz drive, a breathing spring, damping, maybe mass."""
    t = np.arange(int(seconds * RATE)) / RATE
    d = 0.05 * np.sin(2 * np.pi * 5 * t)
    k = 0.5 + 0.4 * np.sin(2 * np.pi * 0.5 * t)
    b = 5e-5 * (1 + np.sin(2 * np.pi * 3 * t))
    m = 2e-6 * (1 + np.sin(2 * np.pi * 1 * t)) if mass else None
    size = int(0.1 * RATE)
    return [
        CoefficientBlock(
            d[i : i + size],
            k[i : i + size],
            b[i : i + size],
            None if m is None else m[i : i + size],
        )  # fmt: skip
        for i in range(0, t.size, size)
    ]


def bare_loop(n: int) -> float:
    """Seconds for a Python loop of n iterations doing one multiply-add (the baseline)."""
    x, start = 0.0, time.perf_counter()
    for i in range(n):
        x = x * 0.5 + i
    return time.perf_counter() - start


def first_block(cache: str) -> float:
    """Seconds for the first 0.1 s block in a new process whose numba cache is `cache`."""
    env = {**os.environ, "NUMBA_CACHE_DIR": cache}
    run = [sys.executable, "-c", FIRST_BLOCK]
    return float(subprocess.run(run, env=env, capture_output=True, text=True, check=True).stdout)


def play(blocks: list[CoefficientBlock], hand: str) -> float:
    knob = KnobPhysics()
    knob.start(Hand.parse(hand))
    start = time.perf_counter()
    for block in blocks:
        knob.run_block(block)
    return time.perf_counter() - start


def run(quick: bool, out: Path) -> list[Table]:
    seconds = 2.0 if quick else 10.0
    n = int(seconds * RATE)
    table = Table(
        f"Simulated knob: {seconds:g} s icon at 10 kHz, paper's knob, best of 3",
        ["case", "x real time", "us per servo period", "/ bare loop step"],
    )
    cases = {}
    for hand in ("hold", "turn:90", "free"):
        for mass in (False, True):
            blocks = icon(seconds, mass)
            best, base = math.inf, math.inf
            for _ in range(3):
                best = min(best, play(blocks, hand))
                base = min(base, bare_loop(n))
            case = f"hand {hand}, {'with' if mass else 'no'} mass"
            cases[case] = seconds / best
            table.rows.append([case, seconds / best, best / n * 1e6, best / base])
    worst = min(cases.values())
    if quick:  # two fresh processes would add seconds to CI's quick run
        table.notes.append("first block in a new process: measured without --quick")
    else:
        with tempfile.TemporaryDirectory() as cache:
            compiled, loaded = first_block(cache), first_block(cache)
        table.notes.append(
            f"first block in a new process: {compiled:.2f} s with an empty numba cache (compiling "
            f"the loop), {loaded:.2f} s with the loop in the cache (later blocks: the table)"
        )
    table.notes += [
        f"target: at least {TARGET:g}x real time: slowest case {worst:.0f}x "
        f"({'met' if worst >= TARGET else 'NOT met'})",
        "bare loop: `x = x * 0.5 + i` for the same number of steps, in this process",
    ]
    plot(cases, out)
    return [table]


def plot(cases: dict[str, float], out: Path) -> None:
    fig, ax = figure(7.0, 3.6)
    y = np.arange(len(cases))[::-1]
    ax.barh(y, list(cases.values()), color="C0")
    ax.axvline(TARGET, color="C3", ls="--", label=f"target {TARGET:g}x")
    ax.set_yticks(y, list(cases), fontsize=8)
    ax.set_xlabel("x real time (higher is faster)")
    ax.set_title("Simulated knob speed at 10 kHz", fontsize=10)
    ax.legend(fontsize=8, loc="lower right")
    save(fig, out, "sim_speed")
