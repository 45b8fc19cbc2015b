"""Cost against size: edits, save/load, hour-long recordings and start-up, each against a baseline.

Every figure is a ratio to something measured in the same process a moment before, so a loaded
machine slows both sides alike:

* edits: the cost of one add_tile + add_clip at the end of a 16,000-clip build against the same
  at its start (O(log n) edits keep this near 1), and the absolute ms per call;
* save/load: projectfile.dumps / loads of 100,000 clips against json's C encoder / decoder on the
  same document (the floor of any JSON file);
* recording: building the peak pyramid of an hour at 44.1 kHz against one pass over its samples,
  and a paint's column query at every zoom against the same pass;
* start-up: CPU of `haptic-timeline --help` and of rendering an example, above a bare Python;
* first render (not with --quick): a fresh process's first render of distinct clips against its
  second, with numba's cache warm and cold.
"""

from __future__ import annotations

import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

import numpy as np

from timeline import edits
from timeline.bench.report import Table, best_cpu_time, best_time, figure, save
from timeline.bench.scenes import LargeSpec, large_project
from timeline.files import projectfile
from timeline.tiles import generator

NAME = "scale"
SUMMARY = "edits, save/load, hour-long recordings and start-up against in-process baselines"
PROJECTS = Path(__file__).resolve().parents[2] / "projects"
TARGET_EDIT_MS = 0.1
TARGET_FILE_S = 1.0
TARGET_PAINT_S = 0.016
TARGET_STARTUP_S = 0.1
TARGET_RENDER_CPU_S = 0.25
TARGET_DISTINCT_RATIO = 10.0


def edit_costs(clips: int, tracks: int = 64) -> dict[str, float]:
    """Seconds per add_tile + add_clip pair over the first and the last quarter of a build
    (at most 1,000 pairs each), in process time."""
    project = edits.new_project(templates=False)
    track_ids = []
    for _ in range(tracks):
        project, track_id = edits.add_track(project, "drive")
        track_ids.append(track_id)
    window = min(1000, clips // 4)
    marks = {}
    start = time.process_time()
    for i in range(clips):
        if i in (window, clips - window):
            marks[i] = time.process_time()
        tile = generator("sine", 1.0, frequency=10.0 + 0.001 * i)
        project, tile_id = edits.add_tile(project, tile)
        project, _ = edits.add_clip(project, track_ids[i % tracks], tile_id, (i * 0.37) % 600)
    end = time.process_time()
    return {
        "first": (marks[window] - start) / window,
        "last": (end - marks[clips - window]) / window,
    }


def file_costs(clips: int, repeat: int) -> dict[str, float]:
    """dumps/loads of a project of `clips` clips and json's C encoder/decoder on the same data."""
    project = large_project(LargeSpec(64, clips, 600.0, 200))
    doc = projectfile.to_json(project)
    text = projectfile.dumps(project)
    return {
        "clips": sum(len(t.clips) for t in project.tracks),
        "mb": len(text) / 1e6,
        "dumps": best_time(lambda: projectfile.dumps(project), repeat),
        "json_dumps": best_time(lambda: json.dumps(doc), repeat),
        "loads": best_time(lambda: projectfile.loads(text), repeat),
        "json_loads": best_time(lambda: json.loads(text), repeat),
    }


def recording_costs(seconds: float, repeat: int) -> dict[str, float]:
    """Peak pyramid build and the slowest paint query against one pass over the samples."""
    from timeline.gui.peaks import PeakPyramid

    rate = 44_100.0
    n = int(seconds * rate)
    rng = np.random.default_rng(1)
    data = np.sin(2 * np.pi * 120.0 * np.arange(n) / rate) * 0.5 + 0.01 * rng.standard_normal(n)
    one_pass = best_time(lambda: float(np.max(data)), repeat)
    build = best_time(lambda: PeakPyramid(data), repeat)
    pyramid = PeakPyramid(data)
    width = 1400
    paints = {}
    for span in (seconds, 600.0, 60.0, 1.0, 0.01):  # whole recording down to 10 ms per window
        span = min(span, seconds)
        first = (seconds - span) * 0.5 * rate
        paints[span] = best_time(
            lambda f=first, s=span: pyramid.columns(f, f + s * rate, width), repeat
        )
    level_bytes = sum(lo.nbytes + hi.nbytes for _, lo, hi in pyramid.levels)
    return {"seconds": seconds, "pass": one_pass, "build": build, "paint": max(paints.values()),
            "level_mb": level_bytes / 1e6, "data_mb": data.nbytes / 1e6}  # fmt: skip


def _child_cpu(argv: list[str], env: dict[str, str]) -> float:
    """CPU seconds (user + system) one child process took."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(argv, capture_output=True, check=True, env=env)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def startup_costs(repeat: int) -> dict[str, float]:
    """Least CPU of bare Python, `--help` and rendering an example to CSV, over `repeat` runs.

    Each command runs once first, so the runs measured find the modules' bytecode cached, as a
    user's second run does (in a temporary folder: PYTHONDONTWRITEBYTECODE, if set, would have
    every run compile the project's modules again, 0.05-0.08 s here).
    """
    cli = [sys.executable, "-m", "timeline.cli.main"]
    with tempfile.TemporaryDirectory() as tmp:
        env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
        env["PYTHONPYCACHEPREFIX"] = os.path.join(tmp, "bytecode")
        out = os.path.join(tmp, "out.csv")
        runs = {
            "python": [sys.executable, "-c", "pass"],
            "help": [*cli, "--help"],
            "render": [*cli, "render", str(PROJECTS / "rising_resistance.htl"), "-o", out],
        }
        for argv in runs.values():
            _child_cpu(argv, env)
        return {
            name: min(_child_cpu(argv, env) for _ in range(repeat)) for name, argv in runs.items()
        }


def render_costs(clips: int, seconds: float, repeat: int, profile: bool = False) -> dict[str, Any]:
    """Full render of every-clip-distinct, off-grid clips on 64 tracks against a memory pass, and
    the evaluation floor: the same samples evaluated in batches, without per-clip work; with
    `profile`, its CPU per stage and the libm calls it needs (timeline.bench.render_profile)."""
    from timeline.bench.eval_floor import evaluation_work, run_all
    from timeline.bench.mixer_speed import fresh_render, memory_pass
    from timeline.bench.scenes import clip_samples
    from timeline.rendering.mixer import Mixer

    project = large_project(LargeSpec(64, clips, seconds, 0, off_grid=True))
    total = clip_samples(project, project.rate)
    # the first 30 s once, not timed: imports and numba's cached loops, which the full render
    # would otherwise load inside the timing when it is run once (16,000 clips)
    Mixer().render(project, 0.0, min(seconds, 30.0))
    full = best_cpu_time(lambda: fresh_render(project, seconds), repeat)
    n = int(round(seconds * project.rate))
    base = best_cpu_time(lambda: memory_pass(total, n, 1), repeat)
    works = evaluation_work(project, 0.0, seconds)
    run_all(works)  # soxr's and numba's first calls, not timed
    floor = best_cpu_time(lambda: run_all(works), repeat)
    costs: dict[str, Any] = {"clips": clips, "full": full, "pass": base, "evaluate": floor}
    if profile:
        from timeline.bench.render_profile import libm_seconds, stage_seconds

        costs["stages"] = stage_seconds(lambda: fresh_render(project, seconds))
        costs["libm"], costs["libm_calls"] = libm_seconds(project, seconds)
    return costs


def profile_table(top: dict[str, Any]) -> Table:
    """The largest render's CPU per stage, each as a ratio to the memory pass, and its floor."""
    base, stages = top["pass"], top["stages"]
    table = Table(f"Scale: where the full render of {top['clips']:,} distinct clips spends its CPU",
                  ["stage", "CPU s", "/ memory pass"])  # fmt: skip
    for name, spent in sorted(stages.items(), key=lambda kv: -kv[1]):
        table.rows.append([name, spent, spent / base])
    whole = sum(stages.values())
    table.rows.append(["the profiled render", whole, whole / base])
    fourier = stages.get("square: Fourier sum", 0.0)
    floor = top["libm"] + fourier
    table.notes += [
        "each stage: the exclusive CPU of the functions doing it, timed inside one full render "
        "(less the clock's own cost per call); bookkeeping: the rest of that render's CPU",
        f"floor of any render with these bits: the {top['libm_calls']:,} sin/cos evaluations of "
        f"the numpy forms, timed call by call, {top['libm']:.3f} s "
        f"({1e9 * top['libm'] / max(1, top['libm_calls']):.1f} ns each, "
        f"{top['libm'] / base:.2f}x the pass), plus the square's Fourier sum {fourier:.3f} s: "
        f"{floor / base:.2f}x the memory pass",
    ]
    return table


_FIRST_RENDER = """
import sys, time
from timeline.bench.scenes import LargeSpec, large_project
from timeline.rendering.mixer import Mixer
project = large_project(LargeSpec(64, 1000, 60.0, 0, off_grid=True))
times = []
for _ in range(2):
    start = time.process_time()
    Mixer().render(project, 0.0, 60.0)
    times.append(time.process_time() - start)
print(times[0], times[1], "numba" in sys.modules)
"""


def first_render_costs() -> dict[str, float]:
    """CPU of the first and second render of 1,000 distinct clips (60 s) in a fresh process,
    with numba's cache as it is and with an empty one (every loop compiled in the first)."""
    costs = {}
    with tempfile.TemporaryDirectory() as tmp:
        for name, extra in (("cached", {}), ("cold", {"NUMBA_CACHE_DIR": tmp})):
            env = {**os.environ, **extra}
            done = subprocess.run([sys.executable, "-c", _FIRST_RENDER], capture_output=True,
                                  text=True, check=True, env=env)  # fmt: skip
            first, second, numba = done.stdout.split()
            costs[name] = float(first)
            costs[f"{name} second"] = float(second)
            costs["numba"] = float(numba == "True")
    return costs


def run(quick: bool, out: Path) -> list[Table]:
    repeat = 2 if quick else 3
    render_sizes = ((250, 15.0), (1_000, 30.0)) if quick else ((1_000, 60.0), (4_000, 150.0),
                                                                (16_000, 600.0))  # fmt: skip
    renders = [render_costs(n, s, 1 if n > 4_000 else repeat, profile=(n, s) == render_sizes[-1])
               for n, s in render_sizes]  # fmt: skip
    sizes = (500, 2_000) if quick else (1_000, 4_000, 16_000)
    builds = {n: edit_costs(n) for n in sizes}
    file_sizes = (1_000, 5_000) if quick else (10_000, 30_000, 100_000)
    files = [file_costs(n, repeat) for n in file_sizes]
    durations = (30.0, 120.0) if quick else (60.0, 600.0, 3600.0)
    recordings = [recording_costs(s, repeat) for s in durations]
    start = startup_costs(1 if quick else 3)

    edit_table = Table("Scale: building through edits (64 tracks, one tile per clip)",
                       ["clips", "ms per pair, first quarter", "ms per pair, last quarter",
                        "last / first", "ms per call (last)"])  # fmt: skip
    for n, cost in builds.items():
        edit_table.rows.append([n, 1e3 * cost["first"], 1e3 * cost["last"],
                                cost["last"] / cost["first"], 1e3 * cost["last"] / 2])  # fmt: skip
    top = builds[sizes[-1]]
    edit_table.notes.append(
        f"target: <= {TARGET_EDIT_MS} ms per add_tile/add_clip at 16,000 clips: "
        f"{1e3 * top['last'] / 2:.3f} ms at {sizes[-1]} "
        f"({'met' if 1e3 * top['last'] / 2 <= TARGET_EDIT_MS else 'NOT met'}); process time"
    )

    file_table = Table("Scale: project save and load",
                       ["clips", "MB", "dumps s", "json C encode s", "dumps / json",
                        "loads s", "json C decode s", "loads / json"])  # fmt: skip
    for f in files:
        file_table.rows.append([f["clips"], f["mb"], f["dumps"], f["json_dumps"],
                                f["dumps"] / f["json_dumps"], f["loads"], f["json_loads"],
                                f["loads"] / f["json_loads"]])  # fmt: skip
    big = files[-1]
    file_table.notes.append(
        f"target: save and load of 100,000 clips <= {TARGET_FILE_S:g} s each: dumps "
        f"{big['dumps']:.2f} s, loads {big['loads']:.2f} s at {big['clips']} clips"
    )

    rec_table = Table("Scale: peak pyramid of a 44.1 kHz recording (1,400 px columns)",
                      ["seconds", "samples MB", "levels MB", "one pass s", "build s",
                       "build / pass", "slowest paint query s", "paint / pass"])  # fmt: skip
    for r in recordings:
        rec_table.rows.append([r["seconds"], r["data_mb"], r["level_mb"], r["pass"], r["build"],
                               r["build"] / r["pass"], r["paint"],
                               r["paint"] / r["pass"]])  # fmt: skip
    rec_table.notes.append(
        f"target: a paint's query well inside {1e3 * TARGET_PAINT_S:g} ms at every zoom "
        f"(whole recording, 10 min, 1 min, 1 s, 10 ms windows): slowest "
        f"{1e3 * recordings[-1]['paint']:.3f} ms at {recordings[-1]['seconds']:g} s"
    )

    help_cpu = start["help"] - start["python"]
    render_cpu = start["render"] - start["python"]
    start_table = Table("Scale: start-up CPU above a bare Python",
                        ["run", "CPU s", "above bare Python s", "target s"])  # fmt: skip
    start_table.rows += [
        ["python -c pass", start["python"], 0.0, ""],
        ["haptic-timeline --help", start["help"], help_cpu, TARGET_STARTUP_S],
        ["render rising_resistance.htl", start["render"], render_cpu, TARGET_RENDER_CPU_S],
    ]
    start_table.notes.append(
        f"least of {1 if quick else 3} run(s) after a warm-up run (bytecode cached); user + "
        f"system CPU of each child process"
    )
    render_table = Table("Scale: full render, every clip its own shape, off-grid starts, 64 tracks",
                         ["clips", "memory pass CPU s", "floor CPU s", "full render CPU s",
                          "floor / pass", "full / pass", "bookkeeping / pass"])  # fmt: skip
    for r in renders:
        floor, base = r["evaluate"] + r["pass"], r["pass"]
        render_table.rows.append([r["clips"], base, floor, r["full"], floor / base,
                                  r["full"] / base, (r["full"] - floor) / base])  # fmt: skip
    top = renders[-1]
    ratio = top["full"] / top["pass"]
    render_table.notes += [
        f"target: <= {TARGET_DISTINCT_RATIO:g}x the memory pass at 16,000-20,000 distinct clips, "
        f"the same bits as numpy's forms: {ratio:.1f}x at {top['clips']} clips "
        f"({'met' if ratio <= TARGET_DISTINCT_RATIO else 'NOT met'}); CPU time",
        "floor: every clip sample evaluated once with the mixer's own functions, batched per "
        "(tile, spacing) (timeline.bench.eval_floor), plus one memory pass to add them; "
        "bookkeeping: the rest of the full render (placing, per-clip calls, scaling, fades' "
        "multiply)",
    ]
    tables = [render_table, profile_table(top), edit_table, file_table, rec_table, start_table]
    if not quick:  # a cold numba cache compiles every loop: ~1 min, left out of --quick
        first = first_render_costs()
        first_table = Table("Scale: first render in a fresh process, 1,000 distinct clips (60 s)",
                            ["numba cache", "first render CPU s", "second render CPU s",
                             "first - second s"])  # fmt: skip
        for name in ("cached", "cold"):
            first_table.rows.append([name, first[name], first[f"{name} second"],
                                     first[name] - first[f"{name} second"]])  # fmt: skip
        first_table.notes.append(
            "first - second: loading numba and its loops (cached: read from __pycache__; cold: "
            "compiled, as after an install or an edit of timeline/signal/*_kernels.py)"
        )
        tables.append(first_table)
    plot(builds, files, recordings, renders, out)
    return tables


def plot(builds: dict[int, dict], files: list[dict], recordings: list[dict], renders: list[dict],
         out: Path) -> None:  # fmt: skip
    """Log-log: cost against clips (render, edits, save, load) and against recording length."""
    fig, (by_clips, by_length) = figure(9.0, 3.8, ncols=2)
    by_clips.loglog([r["clips"] for r in renders], [1e3 * r["full"] for r in renders], "D-",
                    label="full render, distinct clips (ms)")  # fmt: skip
    by_clips.loglog([r["clips"] for r in renders],
                    [1e3 * (r["evaluate"] + r["pass"]) for r in renders], "D--", color="C0",
                    label="evaluation floor of that render (ms)")  # fmt: skip
    by_clips.loglog([r["clips"] for r in renders], [1e3 * r["pass"] for r in renders], ":",
                    color="0.5", label="memory pass (ms)")  # fmt: skip
    sizes = sorted(builds)
    by_clips.loglog(sizes, [1e3 * builds[n]["last"] / 2 for n in sizes], "o-",
                    label="one edit (ms), at the end of a build")  # fmt: skip
    clips = [f["clips"] for f in files]
    by_clips.loglog(clips, [1e3 * f["dumps"] for f in files], "s-", label="save (ms)")
    by_clips.loglog(clips, [1e3 * f["loads"] for f in files], "^-", label="load (ms)")
    by_clips.set_xlabel("clips")
    by_clips.set_ylabel("cost (ms, log)")
    by_clips.legend(fontsize=7)
    seconds = [r["seconds"] for r in recordings]
    by_length.loglog(seconds, [1e3 * r["build"] for r in recordings], "o-",
                     label="peak pyramid build (ms)")  # fmt: skip
    by_length.loglog(seconds, [1e3 * r["paint"] for r in recordings], "s-",
                     label="slowest paint query (ms)")  # fmt: skip
    by_length.loglog(seconds, [1e3 * r["pass"] for r in recordings], ":", color="0.5",
                     label="one pass over the samples (ms)")  # fmt: skip
    by_length.set_xlabel("recording length (s, 44.1 kHz)")
    by_length.legend(fontsize=7)
    fig.suptitle("Cost against size", fontsize=10)
    save(fig, out, "scale")
