"""Hour-long recording: import it, open the editor on it, repaint it at every zoom.

Imports an audio file into a new project in this process (what the editor's File > Import does),
opens the main window on the project (offscreen) and grabs it, so the first paint with the
waveform is done, then repaints the timeline at zooms from the whole recording down to 10 ms per
window, then saves the project and loads it back (each in a process of its own). Prints wall and
CPU seconds and the peak resident memory after each step, with the load average, against the
targets of issue 11 (import and open <= 5 s wall, peak <= 1 GB, repaint <= 16 ms; GB are 10^9
bytes; and issue 19's for the project file: save and load <= 2 s, peak <= 1.5x the samples).
Without --file it writes a 16-bit PCM WAV of --seconds at 44.1 kHz to a temporary folder
first (never inside the project). To compare with other code in the same conditions, run this
file with PYTHONPATH set to that code's tree.

    QT_QPA_PLATFORM=offscreen python benchmarks/long_recording.py [--seconds 3600]
        [--channels 1|2] [--file recording.wav]
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

from timeline.bench.child_process import cpu_seconds, peak_rss  # noqa: E402 - after the Qt platform

RATE = 44_100
GB = 1e9


def write_recording(path: Path, seconds: float, channels: int) -> None:
    """A 16-bit PCM WAV: an 80 Hz tone under a slow envelope, with noise, written in blocks."""
    import numpy as np
    import soundfile as sf

    rng = np.random.default_rng(1)
    total = int(seconds * RATE)
    with sf.SoundFile(path, "w", RATE, channels, subtype="PCM_16") as f:
        for first in range(0, total, 1 << 20):
            t = (first + np.arange(min(1 << 20, total - first))) / RATE
            wave = 0.5 * np.sin(2 * np.pi * 80 * t) * (0.5 + 0.5 * np.sin(2 * np.pi * 0.05 * t))
            wave += 0.05 * rng.standard_normal(t.size)
            f.write(np.repeat(wave[:, None], channels, axis=1))


def measured(what: str, work: Callable[[], Any]) -> tuple[Any, dict[str, float]]:
    """Run work once; its result and its wall, CPU and the peak RSS after it."""
    wall, cpu = time.perf_counter(), cpu_seconds()
    result = work()
    row = {"wall": time.perf_counter() - wall, "cpu": cpu_seconds() - cpu, "rss": peak_rss()}
    print(f"{what:<28} {row['wall']:7.2f} s wall {row['cpu']:7.2f} s CPU   "
          f"peak RSS {row['rss'] / GB:6.3f} GB", flush=True)  # fmt: skip
    return result, row


def repaint_ms(window, px_per_unit: float, repeat: int) -> tuple[float, float]:
    """Median wall and GUI-thread CPU ms of `repeat` synchronous repaints of the timeline."""
    view = window.view
    view.geometry.px_per_unit = px_per_unit
    view.refresh()
    view.viewport().repaint()  # the first paint at a zoom may build the scene's items
    walls, cpus = [], []
    for _ in range(repeat):
        wall, cpu = time.perf_counter(), time.thread_time()
        view.viewport().repaint()
        walls.append(time.perf_counter() - wall)
        cpus.append(time.thread_time() - cpu)
    return 1e3 * statistics.median(walls), 1e3 * statistics.median(cpus)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=3600.0)
    parser.add_argument("--channels", type=int, default=1)
    parser.add_argument("--file", type=Path, help="an existing recording to use instead")
    parser.add_argument("--repeat", type=int, default=5, help="repaints per zoom")
    parser.add_argument("--step", choices=("save", "load"), help=argparse.SUPPRESS)
    parser.add_argument("--project", type=Path, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.step:  # one project-file step in a process of its own, for its own peak memory
        project_file_step(args.step, args.file, args.project)
        return
    with tempfile.TemporaryDirectory() as tmp:
        path = args.file
        if path is None:
            path = Path(tmp) / "recording.wav"
            write_recording(path, args.seconds, args.channels)
        run(path, args.repeat)
        for step in ("save", "load"):
            argv = ["--step", step, "--file", str(path), "--project", str(Path(tmp) / "p.htl")]
            subprocess.run([sys.executable, __file__, *argv], check=True)


def project_file_step(step: str, path: Path, project_path: Path) -> None:
    """Save (after importing the recording) or load the project file, measured alone."""
    from timeline import edits
    from timeline.files import importing, projectfile

    if step == "save":
        project, _ = importing.import_file(edits.new_project(), path)
        print(f"{'(import again, for saving)':<28} peak RSS {peak_rss() / GB:6.3f} GB")
        _, row = measured("save the project", lambda: projectfile.save(project, project_path))
        print(f"{'':<28} the file is {project_path.stat().st_size / 1e6:.0f} MB")
    else:
        project, row = measured("load the project", lambda: projectfile.load(project_path))
    samples = sum(t.data.nbytes for t in project.tiles.values() if hasattr(t, "data"))
    print(f"{'':<28} peak {row['rss'] / samples:.2f}x the samples' {samples / 1e6:.0f} MB "
          f"(issue 19: save and load <= 2 s, peak <= 1.5x: "
          f"{_met(row['wall'] <= 2 and row['rss'] <= 1.5 * samples)})")  # fmt: skip


def run(path: Path, repeat: int) -> None:
    print(f"{path.name}: {path.stat().st_size / 1e6:.0f} MB, load average "
          f"{' '.join(f'{x:.1f}' for x in os.getloadavg())}", flush=True)  # fmt: skip
    base_rss = peak_rss()
    from PySide6.QtWidgets import QApplication

    from timeline import edits
    from timeline.files import importing
    from timeline.gui.main_window import MainWindow

    app = QApplication.instance() or QApplication(sys.argv[:1])
    print(f"{'python, Qt and the editor':<28} peak RSS {peak_rss() / GB:5.2f} GB "
          f"(from {base_rss / GB:.2f})", flush=True)  # fmt: skip
    (project, _), imported = measured(
        "import", lambda: importing.import_file(edits.new_project(), path)
    )

    def open_window():
        window = MainWindow(project)
        window.resize(1400, 900)
        window.show()
        window.view.fit()
        app.processEvents()
        window.grab()  # paints every widget now: the first paint with the waveform is done
        return window

    window, opened = measured("open (first paint done)", open_window)
    fit = window.view.geometry.px_per_unit
    duration = project.duration
    width = window.view.viewport().width()
    worst = 0.0
    for span in (duration, 600.0, 60.0, 10.0, 1.0, 0.01):  # the whole recording down to 10 ms
        span = min(span, duration)
        ms, cpu_ms = repaint_ms(window, fit * duration / span, repeat)
        worst = max(worst, ms)
        print(f"repaint, {span:>8g} s in {width} px   {ms:7.2f} ms wall {cpu_ms:7.2f} ms CPU",
              flush=True)  # fmt: skip
    total = imported["wall"] + opened["wall"]
    peak = peak_rss()
    print(f"import and open: {total:.2f} s wall (target <= 5 s: {_met(total <= 5)}); "
          f"peak RSS {peak / GB:.3f} GB (<= 1 GB: {_met(peak <= GB)}); slowest repaint "
          f"{worst:.2f} ms (<= 16 ms: {_met(worst <= 16)}); load average "
          f"{' '.join(f'{x:.1f}' for x in os.getloadavg())}")  # fmt: skip
    window.close()


def _met(ok: bool) -> str:
    return "met" if ok else "NOT met"


if __name__ == "__main__":
    main()
