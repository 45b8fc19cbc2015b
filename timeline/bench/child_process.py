"""A benchmark step in a process of its own, so its peak resident memory is its own."""

from __future__ import annotations

import json
import resource
import subprocess
import sys
from typing import Any


def process_status(field: str) -> float | None:
    """A memory line of this process's /proc status (e.g. "VmRSS"), in bytes; None where there
    is no /proc."""
    try:
        with open("/proc/self/status", encoding="ascii") as status:
            for line in status:
                if line.startswith(field + ":"):
                    return float(line.split()[1]) * 1024.0
    except OSError:
        pass
    return None


def peak_rss() -> float:
    """Peak resident memory of this process so far, in bytes: VmHWM on Linux (ru_maxrss would
    carry a parent's peak over into a child it execs), else ru_maxrss."""
    peak = process_status("VmHWM")
    if peak is not None:
        return peak
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024.0  # KiB on Linux


def cpu_seconds() -> float:
    """User + system CPU of this process so far, every thread included."""
    usage = resource.getrusage(resource.RUSAGE_SELF)
    return usage.ru_utime + usage.ru_stime


def run_child(module: str, *args: str) -> dict[str, Any]:
    """Run `python -m module args` and return the JSON object its last output line prints."""
    done = subprocess.run(
        [sys.executable, "-m", module, *args], check=True, capture_output=True, text=True
    )
    return json.loads(done.stdout.strip().splitlines()[-1])


def report(result: dict[str, Any]) -> None:
    """A child's result, as the last line of its output (what run_child reads)."""
    print(json.dumps(result), flush=True)
