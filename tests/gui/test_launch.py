"""Launch: what waits for the editor's first paint (the autosave, the player's streaming, the
format registry), the garbage collector paused until then, and OpenBLAS held to one thread."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

EXAMPLE = Path(__file__).resolve().parents[2] / "projects" / "fan_knob.htl"
AFTER_FIRST_PAINT = (
    # the autosave journal and where it lives
    "timeline.gui.autosave", "timeline.files.journal", "platformdirs",
    # what playing needs: the live stream, device programs and telemetry, position tables
    "timeline.gui.live_stream", "timeline.plugins.device_protocol.device",
    "timeline.plugins.device_protocol.telemetry", "timeline.rendering.playback", "csv",
    # the import formats' registry and the breakpoint analysis of designs
    "timeline.plugins.file_formats", "timeline.analysis.breakpoints",
    # the sound analysis's settings and their panel (with the import dock first shown), and
    # the recordings' content hash (with the first recording)
    "timeline.analysis.settings", "timeline.gui.analysis_panel", "hashlib",
    # the lanes' gestures (every one is built on the base; the palette's drop is not)
    "timeline.gui.gestures.base", "timeline.gui.gestures.palette_drop",
)  # fmt: skip

PROBE = """
import gc, json, os, sys
from PySide6.QtCore import QTimer
from timeline.gui.app import launch
from timeline.gui.first_paint import after_first_paint
app, window = launch(sys.argv[1])
seen = {"blas threads": os.environ.get("OPENBLAS_NUM_THREADS"), "collecting": [gc.isenabled()]}
def after():  # once what waits for the first paint has run
    try:
        seen["collecting"].append(gc.isenabled())
        seen["autosaving"] = getattr(window, "_autosaver", None) is not None  # not asked for
    finally:
        window.close()
        app.quit()
def painted():
    seen["loaded"] = [m for m in sys.argv[2:] if m in sys.modules]
    seen["collecting"].append(gc.isenabled())
    QTimer.singleShot(0, after)
after_first_paint(window.view.viewport(), painted)
app.exec()
print(json.dumps(seen))
"""


def test_the_first_paint_waits_for_neither_autosave_nor_playing_nor_formats(tmp_path):
    env = {k: v for k, v in os.environ.items() if k != "OPENBLAS_NUM_THREADS"}
    # no autosave of the user's offered, and no window state of theirs (a shown dock) restored
    env.update(QT_QPA_PLATFORM="offscreen", XDG_DATA_HOME=str(tmp_path),
               XDG_CONFIG_HOME=str(tmp_path))  # fmt: skip
    done = subprocess.run(
        [sys.executable, "-c", PROBE, str(EXAMPLE), *AFTER_FIRST_PAINT],
        capture_output=True,
        text=True,
        env=env,
        check=True,
        timeout=120,
    )
    found = json.loads(done.stdout.strip().splitlines()[-1])
    assert found["loaded"] == []
    # the collector is off from the launch to the first paint, on again right after it
    assert found["collecting"] == [False, False, True]
    assert found["autosaving"]
    assert found["blas threads"] == "1"  # as the command line holds it
