"""The AHAP reader's time against its input's size: overlapping continuous events, long curves.

Issue 25.4: 3,000 overlapping continuous events read in 62.7 s (worse than quadratic) and one
curve of 10^6 points in 47.7 s. Each case is timed at doubling sizes; the growth exponent (the
slope of log time against log size between the two largest) says how the reader scales: 1 is
linear, 2 quadratic. Each time is also a ratio to json.loads of the same file.
"""

from __future__ import annotations

import json
import math
import tempfile
from pathlib import Path

import numpy as np

from timeline.bench.report import Table, best_time
from timeline.files import importing

NAME = "ahap-reader"
SUMMARY = "AHAP import time against size: overlapping continuous events, one long curve"
EVENTS = (500, 1_000, 2_000, 4_000)
POINTS = (6_000, 12_000, 24_000, 48_000)  # one curve, under the reader's 50,000-entry cap


def overlapping_events(n: int) -> dict:
    """n continuous events of 1-29 s with attack and release, all within a minute (seeded)."""
    rng = np.random.default_rng(3)
    pattern = []
    for _ in range(n):
        values = {
            "HapticIntensity": rng.uniform(),
            "HapticSharpness": rng.uniform(),
            "AttackTime": rng.uniform(0.0, 0.5),
            "ReleaseTime": rng.uniform(0.0, 0.5),
        }
        event = {
            "Time": round(float(rng.uniform(0.0, 60.0)), 4),
            "EventType": "HapticContinuous",
            "EventDuration": round(float(rng.uniform(1.0, 29.0)), 4),
            "EventParameters": [
                {"ParameterID": k, "ParameterValue": round(float(v), 4)} for k, v in values.items()
            ],
        }
        pattern.append({"Event": event})
    return {"Version": 1.0, "Pattern": pattern}


def long_curve(n: int) -> dict:
    """One 30 s continuous event under one intensity curve of n points."""
    points = [
        {"Time": round(k * 30.0 / n, 6), "ParameterValue": round(0.5 + 0.5 * math.sin(k / 50), 4)}
        for k in range(n)
    ]
    curve = {"ParameterID": "HapticIntensityControl", "Time": 0.0}
    return {
        "Version": 1.0,
        "Pattern": [
            {"Event": {"Time": 0.0, "EventType": "HapticContinuous", "EventDuration": 30.0}},
            {"ParameterCurve": {**curve, "ParameterCurveControlPoints": points}},
        ],
    }


def _rows(label: str, sizes, make, folder: Path, repeat: int) -> list[list[object]]:
    rows, times = [], []
    for n in sizes:
        path = folder / f"{label}{n}.ahap"
        path.write_text(json.dumps(make(n), indent=1))
        text = path.read_bytes()
        parse = best_time(lambda t=text: json.loads(t), repeat)
        seconds = best_time(lambda p=path: importing.read_file(p), repeat)
        times.append(seconds)
        rows.append([label, n, len(text) / 1e3, 1e3 * seconds, 1e6 * seconds / n, seconds / parse])
    growth = math.log(times[-1] / times[-2]) / math.log(sizes[-1] / sizes[-2])
    rows[-1].append(f"{growth:.2f}")
    for row in rows[:-1]:
        row.append("")
    return rows


def run(quick: bool, out: Path) -> list[Table]:
    table = Table(
        "AHAP reader: time against size (best of runs)",
        ["case", "entries", "file KB", "ms", "us per entry", "ratio to json.loads", "growth"],
    )
    repeat = 1 if quick else 3
    events = EVENTS[:3] if quick else EVENTS
    points = POINTS[:3] if quick else POINTS
    with tempfile.TemporaryDirectory() as folder:
        table.rows += _rows("overlapping events", events, overlapping_events, Path(folder), repeat)
        table.rows += _rows("one curve, points", points, long_curve, Path(folder), repeat)
    table.notes.append(
        "growth: slope of log time against log size between the two largest (1 linear, "
        "2 quadratic); every entry and curve point counts against the reader's 50,000 cap"
    )
    return [table]
