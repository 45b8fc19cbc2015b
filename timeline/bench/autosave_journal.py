"""The autosave journal under SIGKILL, and what it costs: edits lost per kill, append CPU per
edit on a 20,000-clip project, the first record's (after an undo too), recovery time.

The kill loop runs the editor's own autosave (timeline.gui.autosave.Autosaver on the editor's
Document, or the whole main window offscreen) in a child process that opens a multi-MB project
(clips and a recording, made by code), edits it every few milliseconds (a clip added, every
fourth step an undo) and snapshots every SNAPSHOT_RECORDS records, so most kills land while a
snapshot is being written. Each child is SIGKILLed at a random moment; this process then
recovers what it left and finds which step the recovered project is. `tests/reliability/
test_autosave_kill.py` asserts on the same loop.
"""

from __future__ import annotations

import argparse
import os
import random
import signal
import statistics
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

NAME = "autosave"
SUMMARY = "autosave journal: edits lost per SIGKILL, append CPU per edit, recovery time"
SNAPSHOT_RECORDS = 10  # in the child: a snapshot is running nearly all the time
EDIT_MS = 5  # between the child's edits
FIRST = 600.0  # the child's clips start here, one second apart


def project_file(path: Path, clips: int, samples: int) -> Path:
    """A project of `clips` clips and a float64 recording of `samples` samples, saved."""
    import numpy as np

    from timeline import edits
    from timeline.bench.scenes import LargeSpec, large_project
    from timeline.files import projectfile
    from timeline.tiles import SampledTile

    spec = LargeSpec(tracks=8, clips=clips, seconds=120.0, shapes=20)
    project = _editable(large_project(spec))
    recording = SampledTile(np.sin(np.arange(samples) / 40.0), 1000.0, "recording")
    project, _ = edits.add_tile(project, recording)
    projectfile.save(project, path)
    return path


def _editable(project):
    """The large project with its next id past its clips' (large_project numbers them c0, c1,
    ... without counting), so a new clip's id is new."""
    from dataclasses import replace

    clips = sum(len(t.clips) for t in project.tracks)
    return replace(project, next_id=project.next_id + clips)


def step_starts(steps: int) -> list[tuple[float, ...]]:
    """The child's added clip starts after each of 0..steps steps (step i adds a clip at
    FIRST + i, every fourth step undoes the last add instead)."""
    done: list[float] = []
    states: list[tuple[float, ...]] = [()]
    for i in range(steps):
        if i % 4 == 3:
            done.pop()
        else:
            done.append(FIRST + i)
        states.append(tuple(done))
    return states


def child(path: Path, window: bool) -> None:
    """Edit the project until killed, printing each step's number once it is applied."""
    from PySide6.QtCore import QTimer

    from timeline import edits
    from timeline.files import projectfile

    project = projectfile.load(path)
    if window:
        from PySide6.QtWidgets import QApplication

        from timeline.gui.main_window import MainWindow

        app = QApplication([])
        win = MainWindow(project, path)
        doc, saver = win.doc, win.autosaver
    else:
        from PySide6.QtCore import QCoreApplication

        from timeline.gui.autosave import Autosaver
        from timeline.gui.document import Document

        app = QCoreApplication([])
        doc = Document(project, path)
        saver = Autosaver(doc)
        saver.on_disk(path)
    saver.journal.snapshot_records = SNAPSHOT_RECORDS
    track = project.tracks[0].id
    tile = next(iter(project.tiles))
    step = iter(range(10**9))

    def edit() -> None:
        i = next(step)
        if i % 4 == 3:
            doc.undo()
        else:
            doc.apply("add clip", edits.add_clip, track, tile, FIRST + i)
        print(i, flush=True)

    timer = QTimer()
    timer.setInterval(EDIT_MS)
    timer.timeout.connect(edit)
    timer.start()
    print("ready", flush=True)
    sys.exit(app.exec())


@dataclass
class Kill:
    """One kill: steps the child applied, the step recovered, and how it went."""

    applied: int
    recovered: int
    during_snapshot: bool
    recovery_s: float
    left: list[str]  # files in the autosave folder after the recovered session was discarded

    @property
    def lost(self) -> int:
        return self.applied - self.recovered


def kill_once(path: Path, data_home: Path, rng: random.Random, window: bool) -> Kill:
    """Run a child on `path`, SIGKILL it at a random moment, recover in this process."""
    from timeline.gui import autosave

    env = {**os.environ, "XDG_DATA_HOME": str(data_home), "QT_QPA_PLATFORM": "offscreen"}
    args = [sys.executable, "-m", __name__, "child", str(path)] + (["--window"] if window else [])
    proc = subprocess.Popen(args, env=env, stdout=subprocess.PIPE)
    assert proc.stdout is not None
    if proc.stdout.readline().strip() != b"ready":
        raise RuntimeError("the autosave child did not start")
    time.sleep(rng.uniform(0.2, 2.0))
    folder = data_home / "haptic-timeline" / "autosave"
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    lines = proc.stdout.read().split()
    proc.stdout.close()
    applied = int(lines[-1]) + 1 if lines else 0
    during = any(".partial-" in p.name for p in folder.rglob("*"))
    os.environ["XDG_DATA_HOME"] = str(data_home)
    start = time.perf_counter()
    found = autosave.recoverable()
    recovered = found[0].load() if found else None
    seconds = time.perf_counter() - start
    starts = ()
    if recovered is not None:
        clips = recovered.tracks[0].clips
        starts = tuple(sorted(c.start for c in clips if c.start >= FIRST))
    states = step_starts(applied + 1)
    at = max((k for k, s in enumerate(states) if s == starts), default=-1)
    for entry in found:
        entry.discard()
    autosave.recoverable()  # the next start's clean-up
    left = sorted(p.name for p in folder.rglob("*"))
    return Kill(applied, at, during, seconds, left)


def kill_loop(kills: int, seed: int, window: bool, clips: int, samples: int) -> list[Kill]:
    """`kills` kills of children editing one project; the XDG data folder is a temporary one."""
    saved = os.environ.get("XDG_DATA_HOME")
    rng = random.Random(seed)
    try:
        with tempfile.TemporaryDirectory() as folder:
            path = project_file(Path(folder) / "design.htl", clips, samples)
            return [kill_once(path, Path(folder) / f"data{i}", rng, window) for i in range(kills)]
    finally:
        if saved is None:
            os.environ.pop("XDG_DATA_HOME", None)
        else:
            os.environ["XDG_DATA_HOME"] = saved


def append_cost(clips: int, edits_count: int = 200) -> dict[str, float]:
    """CPU per journal record for clip moves on the large project (`clips` clips)."""
    from timeline import edits
    from timeline.bench.scenes import LargeSpec, large_project
    from timeline.files import journal, projectfile

    project = _editable(large_project(LargeSpec(clips=clips)))
    rng = random.Random(3)
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "big.htl"
        projectfile.save(project, path)
        j = journal.Journal(Path(folder) / "session", snapshot_records=10**9)
        j.start(project, {"pid": os.getpid(), "path": str(path)}, path)
        cpu = []
        for _ in range(edits_count):
            track = project.tracks[rng.randrange(len(project.tracks))]
            clip = track.clips[rng.randrange(len(track.clips))]
            project = edits.move_clip(project, clip.id, clip.start + rng.uniform(-2.0, 2.0))
            before = time.process_time()
            j.record(project)
            cpu.append(time.process_time() - before)
        size = journal.journal_path(j.folder, 0).stat().st_size
        start = time.perf_counter()
        replayed = journal.replay(j.folder)
        replay_s = time.perf_counter() - start
        assert projectfile.dumps(replayed.project) == projectfile.dumps(project)
        snap_start = time.perf_counter()
        projectfile.save(project, Path(folder) / "snapshot.htl")
        snapshot_s = time.perf_counter() - snap_start
        file_mb = path.stat().st_size / 1e6
        j.remove()
    cpu.sort()
    return {
        "median_ms": 1000 * statistics.median(cpu),
        "p95_ms": 1000 * cpu[int(0.95 * (len(cpu) - 1))],
        "max_ms": 1000 * cpu[-1],
        "bytes_per_edit": size / edits_count,
        "replay_s": replay_s,
        "snapshot_s": snapshot_s,
        "file_mb": file_mb,
    }


def first_record_cost(clips: int) -> dict[str, float]:
    """CPU ms of the first record of a never-saved project (`clips` clips): with no base written,
    with the base written on idle, and after an undo back to that base (the session started
    again at it, as the editor's autosave does)."""
    from timeline import edits
    from timeline.bench.scenes import LargeSpec, large_project
    from timeline.files import journal

    project = large_project(LargeSpec(clips=clips))
    clip = project.tracks[0].clips[3]
    moved = [edits.move_clip(project, clip.id, clip.start + dx) for dx in (0.01, 0.02)]
    meta = {"pid": os.getpid(), "path": ""}
    costs = {}
    with tempfile.TemporaryDirectory() as folder:
        j = journal.Journal(Path(folder) / "session")
        for case in ("no base", "base written", "after an undo"):
            j.start(project, meta)
            if case == "base written":
                j.write_base()
                j.wait()
            edited = moved[1] if case == "after an undo" else moved[0]
            before = time.process_time()
            j.record(edited)
            costs[case] = 1000 * (time.process_time() - before)
        j.remove()
    return costs


def recording_cost(seconds: float) -> dict[str, float]:
    """Wall and CPU seconds of the record that adds a recording of `seconds` (its samples)."""
    from timeline import edits
    from timeline.bench.project_media import recording
    from timeline.files import journal

    tile = recording(seconds)
    project = edits.new_project()
    with tempfile.TemporaryDirectory() as folder:
        j = journal.Journal(Path(folder) / "session", snapshot_records=10**9)
        j.start(project, {"pid": os.getpid(), "path": ""})
        project, _ = edits.add_track(project, "drive")
        j.record(project)  # the journal's first record: the project whole
        added, _ = edits.add_tile(project, tile)
        cpu, start = time.process_time(), time.perf_counter()
        j.record(added)
        wall, cpu = time.perf_counter() - start, time.process_time() - cpu
        j.remove()
    return {"wall": wall, "cpu": cpu, "mb": tile.data.nbytes / 1e6}


def run(quick: bool, out: Path):
    from timeline.bench.report import Table

    clips = 2_000 if quick else 20_000
    cost = append_cost(clips, 50 if quick else 200)
    table = Table(
        f"Journal append per edit (a clip moved) on the {clips:,}-clip large project",
        ["CPU ms median", "p95", "max", "bytes/edit", "replay s", "full save s", "file MB"],
    )
    table.rows.append(
        [
            f"{cost['median_ms']:.2f}",
            f"{cost['p95_ms']:.2f}",
            f"{cost['max_ms']:.2f}",
            f"{cost['bytes_per_edit']:.0f}",
            f"{cost['replay_s']:.2f}",
            f"{cost['snapshot_s']:.2f}",
            f"{cost['file_mb']:.1f}",
        ]
    )
    firsts = first_record_cost(clips)
    first_edit = Table(
        f"The first journal record of a never-saved {clips:,}-clip project (a clip moved)",
        ["case", "CPU ms"],
    )
    first_edit.rows.extend([case, f"{ms:.1f}"] for case, ms in firsts.items())
    seconds = 60.0 if quick else 600.0
    media = recording_cost(seconds)
    first = Table(
        f"Journal append of a {seconds / 60:g}-minute float32 recording at 44.1 kHz "
        f"({media['mb']:.0f} MB), the edit that adds it",
        ["wall s", "CPU s"],
    )
    first.rows.append([f"{media['wall']:.2f}", f"{media['cpu']:.2f}"])
    kills_n = 3 if quick else 30
    kills = kill_loop(kills_n, 7, window=not quick, clips=2_000, samples=1_000_000)
    lost = [max(0, k.lost) for k in kills]
    loop = Table(
        f"{kills_n} SIGKILLs of the editor{' window' if not quick else ''}'s autosave (2,000 "
        f"clips and an 8 MB recording, a snapshot every {SNAPSHOT_RECORDS} records, an edit "
        f"every {EDIT_MS} ms)",
        ["edits applied (mean)", "kills losing 0 / 1 / more", "in-flight edit kept",
         "kills mid-snapshot", "recovery s max", "files left"],
    )  # fmt: skip
    loop.rows.append(
        [
            f"{statistics.mean(k.applied for k in kills):.0f}",
            " / ".join(str(n) for n in (lost.count(0), lost.count(1), sum(x > 1 for x in lost))),
            str(sum(k.lost < 0 for k in kills)),
            str(sum(k.during_snapshot for k in kills)),
            f"{max(k.recovery_s for k in kills):.2f}",
            str(sum(len(k.left) for k in kills)),
        ]
    )
    load = " ".join(f"{x:.1f}" for x in os.getloadavg())
    for t in (table, first_edit, first, loop):
        t.notes.append(f"load average {load}; CPU is this process's (time.process_time)")
    return [table, first_edit, first, loop]


if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    parser.add_argument("role", choices=("child",))
    parser.add_argument("path", type=Path)
    parser.add_argument("--window", action="store_true")
    args = parser.parse_args()
    child(args.path, args.window)
