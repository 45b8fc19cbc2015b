"""Playback in the editor: blocks handed to the device later than the protocol's lead.

Each device runs in a fresh process (timeline.bench.playback_session): the editor, offscreen,
opens the large benchmark project and plays on the simulated knob or on the emulated USB knob
running on the wall clock (HAPTIC_TIMELINE_USB_EMULATE=realtime; streamed from a process of its
own), while the GUI idles, scrolls, zooms and drags a clip; then again with a process spinning
on one core beside it. A block later than the device's lead (the sim 30 ms, the USB knob 120 ms)
is one a real knob would have had to play from an empty queue.
"""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from pathlib import Path

from timeline.bench.report import Table

NAME = "playback"
SUMMARY = "editor playing on the sim and a real-time USB knob while scrolling, zooming, dragging"


def run(quick: bool, out: Path) -> list[Table]:
    clips, seconds = (2_000, 1.0) if quick else (20_000, 4.0)
    runs = [("sim", False)] if quick else [(d, h) for d in ("sim", "usb") for h in (False, True)]
    table = Table(
        f"Playback in the editor while the GUI works: {clips:,} clips, {seconds:g} s per gesture",
        ["device", "hog", "gesture", "lead ms", "blocks", "late", "gaps > 50 ms", "worst ms",
         "first block ms", "machine stopped ms", "named", "ended", "priority", "load"],
    )  # fmt: skip
    sessions = [(d, h, False) for d, h in runs]
    sessions += [] if quick else [("sim", False, True), ("sim", True, True)]  # no editor
    for device, hog, alone in sessions:
        for row in _session(device, clips, seconds, hog, alone):
            table.rows.append(
                [
                    "sim" if device == "sim" else "usb (real time)",
                    "1 core" if hog else "—",
                    row["gesture"],
                    f"{1e3 * row.get('lead', 0.0):.0f}",
                    row.get("blocks", 0),
                    row.get("late", 0),
                    row.get("gaps", 0),
                    f"{1e3 * row.get('worst', 0.0):.1f}",
                    _ms(row.get("first_block")),
                    _ms(row.get("stalled")),
                    _named(row, alone),
                    _ending(row.get("ended", "")),
                    row.get("priority", "—"),
                    f"{row['load']:.1f}",
                ]
            )
    table.notes += [
        "target: 0 blocks later than the lead; --quick plays on the sim only",
        "late: blocks handed over more than the device's lead behind their slot (a real knob's "
        "queue would have run dry); worst: the largest delay behind the slot; first block: "
        "from Play to the first block handed over (the first play follows the editor's warm-up)",
        "machine stopped: the longest time no CPU ran anything (a probe pinned to each CPU at "
        "real-time priority overdue on all at once: on a virtual machine, the host stopping it); "
        "a block handed over in it is late whatever the program does (— where the probes were "
        "not granted real-time priority)",
        "named: the message bar named the late blocks (— where none were late, or with no "
        "editor); ended: how the play ended (the USB knob "
        "stops on an underrun); load: the 1-minute load average when the play ended",
        "each device in a fresh editor process, offscreen Qt; hog: `while True: pass` in "
        "another process; child alone: the play process with no editor (full run only)",
        "priority: what the OS granted the play process's playing thread (prefer_real_time: "
        "real-time where permitted, else nice -10, else normal; "
        "HAPTIC_TIMELINE_PLAY_PRIORITY=normal turns it off)",
    ]
    return [table]


def _session(device: str, clips: int, seconds: float, hog: bool, alone: bool) -> list[dict]:
    env = {**os.environ, "QT_QPA_PLATFORM": "offscreen"}
    if device == "usb":
        env["HAPTIC_TIMELINE_USB_EMULATE"] = "realtime"
    args = [sys.executable, "-m", "timeline.bench.playback_session", "--device", device,
            "--clips", str(clips), "--seconds", str(seconds)]  # fmt: skip
    args += (["--hog"] if hog else []) + (["--alone"] if alone else [])
    done = subprocess.run(args, capture_output=True, text=True, env=env)
    rows = [json.loads(line) for line in done.stdout.splitlines() if line.startswith("{")]
    if done.returncode != 0 or not rows:
        tail = done.stderr.strip().splitlines()[-1:]
        return [{"gesture": f"failed (exit {done.returncode}): {tail}", "load": os.getloadavg()[0]}]
    return rows


def _named(row: dict, alone: bool) -> str:
    """Whether the message bar named the row's late blocks ("—": none late, or no editor)."""
    if alone or not row.get("late"):
        return "—"
    return "yes" if row.get("named") else "NO"


def _ms(seconds: float | None) -> str:
    return "—" if seconds is None else f"{1e3 * seconds:.1f}"


def _ending(message: str) -> str:
    """'' or the device's error, short: "underrun at 1.230 s"."""
    if not message:
        return "played"
    at = re.search(r"at (\d+\.\d+ s)", message)
    what = "underrun" if "ran out of samples" in message else message.split(",")[0][:40]
    return f"{what} at {at.group(1)}" if at else what
