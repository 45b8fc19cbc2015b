"""Edit-to-feel latency in the editor: runs benchmarks/edit_to_feel.py when it and Qt are here.

The script ships with the source tree, not the installed package, so from an installed package
this benchmark reports itself skipped.
"""

from __future__ import annotations

import importlib.util
import os
import subprocess
import sys
from pathlib import Path

from timeline.bench.report import Table

NAME = "edit-to-feel"
SUMMARY = "editor drag to the new mix felt on the simulated knob (needs Qt and the source tree)"
SCRIPT = Path(__file__).resolve().parents[2] / "benchmarks" / "edit_to_feel.py"


def run(quick: bool, out: Path) -> list[Table]:
    table = Table("Edit-to-feel latency (editor, offscreen Qt, simulated knob)", ["result"])
    if not SCRIPT.exists():
        table.rows.append([f"skipped: {SCRIPT} is not here (installed package)"])
        return [table]
    if importlib.util.find_spec("PySide6") is None:
        table.rows.append(["skipped: PySide6 is not installed"])
        return [table]
    env = {**os.environ, "QT_QPA_PLATFORM": "offscreen"}
    edits = "8" if quick else "200"
    done = subprocess.run(
        [sys.executable, str(SCRIPT), "--edits", edits], capture_output=True, text=True, env=env
    )
    lines = [line for line in done.stdout.splitlines() if line.strip()]
    if done.returncode != 0:
        lines.append(f"failed (exit {done.returncode}): {done.stderr.strip().splitlines()[-1:]}")
    table.rows += [[line] for line in lines]
    table.notes.append("target: within the 5-50 ms tactile latency guideline (Kaaresoja 2014)")
    return [table]
