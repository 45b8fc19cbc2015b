"""How long the whole machine was stopped while a benchmark ran: one probe process per CPU.

On a virtual machine the host may stop every virtual CPU at once (its CPU budget spent, or the
host busy: the "steal" column of /proc/stat); no thread of the guest runs then, at any priority,
and a stream's block handed over during such a stop is late whatever the program does. Each
probe is pinned to one CPU at real-time priority (FIFO 1, below the play process's 10) and
sleeps 1 ms at a time; a wake more than OVERDUE late is an interval the probe was not run. The
machine was stopped where every CPU's probe was overdue at once.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys

SLEEP = 0.001  # s a probe sleeps at a time
OVERDUE = 0.002  # s: a wake later than this is counted

PROBE = """
import json, os, select, sys, time
cpu, sleep, late = int(sys.argv[1]), float(sys.argv[2]), float(sys.argv[3])
os.sched_setaffinity(0, {cpu})
try:
    os.sched_setscheduler(0, os.SCHED_FIFO, os.sched_param(1))
    real_time = True
except OSError:
    real_time = False
print("ready", flush=True)
overdue = []
while True:
    due = time.perf_counter() + sleep
    ended = select.select([sys.stdin], [], [], sleep)[0]
    woke = time.perf_counter()
    if woke - due > late:
        overdue.append((due, woke))
    if ended:
        break
print(json.dumps({"real_time": real_time, "overdue": overdue}), flush=True)
"""


def longest_common(overdue: list[list[tuple[float, float]]]) -> float:
    """The longest interval (s) inside an overdue interval of every probe at once."""
    if not overdue:
        return 0.0
    common = overdue[0]
    for other in overdue[1:]:
        common = [
            (max(a0, b0), min(a1, b1))
            for a0, a1 in common
            for b0, b1 in other
            if max(a0, b0) < min(a1, b1)
        ]
    return max((end - start for start, end in common), default=0.0)


class MachineStall:
    """Probes on every CPU from `start` to `stop`, which returns the longest whole-machine stop
    in seconds (None where a probe was not granted real-time priority, as an ordinary probe's
    wait for a core would be counted as a stop, or where the OS cannot pin one to a CPU)."""

    def __init__(self) -> None:
        self._probes: list[subprocess.Popen[str]] = []

    def start(self) -> None:
        if not hasattr(os, "sched_getaffinity"):  # Linux only, as the priority asked for
            return
        cpus = sorted(os.sched_getaffinity(0))
        self._probes = [
            subprocess.Popen(
                [sys.executable, "-c", PROBE, str(cpu), str(SLEEP), str(OVERDUE)],
                stdin=subprocess.PIPE,
                stdout=subprocess.PIPE,
                text=True,
            )
            for cpu in cpus
        ]
        for probe in self._probes:  # running: a stall from here on is seen
            assert probe.stdout is not None
            probe.stdout.readline()

    def stop(self) -> float | None:
        answers = [json.loads(probe.communicate("")[0] or "{}") for probe in self._probes]
        self._probes = []
        if not answers or not all(a.get("real_time") for a in answers):
            return None
        return longest_common([[tuple(i) for i in a["overdue"]] for a in answers])
