"""Helpers for a process that streams to a device (the USB knob's, the editor's play process):
ending it, and asking the OS to run its playing thread ahead of ordinary programs."""

from __future__ import annotations

import os
from collections.abc import Iterator
from contextlib import contextmanager, suppress
from multiprocessing.connection import Connection
from multiprocessing.process import BaseProcess

PRIORITY_ENV = "HAPTIC_TIMELINE_PLAY_PRIORITY"  # "normal": play at the ordinary priority
REAL_TIME_PRIORITY = 10  # the round-robin real-time priority asked for (1-99; audio uses 5-20)
NICE = -10  # the niceness asked for where real-time scheduling is not permitted


def end_child(process: BaseProcess, to_child: Connection, *others: Connection) -> None:
    """Ask the child to go ("close"), make sure it went (terminated after 2 s), and close the
    connections to it."""
    with suppress(OSError, ValueError):  # the child may be gone, the pipe with it
        to_child.send(("close",))
    process.join(timeout=2.0)
    if process.is_alive():
        process.terminate()
        process.join(timeout=2.0)
    for conn in (to_child, *others):
        conn.close()


def prefer_real_time() -> str:
    """Run the calling thread, and the threads it starts from now on, ahead of ordinary
    programs, as audio programs do: round-robin real-time scheduling where permitted (root,
    CAP_SYS_NICE, or an rtprio limit such as an audio group's), else a higher priority (nice
    -10); on a loaded machine an ordinary thread waits tens of ms for a core, longer than the
    sim's 30 ms lead. Returns what was granted: "real-time", "nice -10" or "" (neither
    permitted, or HAPTIC_TIMELINE_PLAY_PRIORITY=normal)."""
    if os.environ.get(PRIORITY_ENV) == "normal" or not hasattr(os, "sched_setscheduler"):
        return ""
    import resource  # POSIX only, as sched_setscheduler

    limit = resource.getrlimit(resource.RLIMIT_RTPRIO)[0]
    for priority in (REAL_TIME_PRIORITY, min(REAL_TIME_PRIORITY, limit)):
        if priority > 0:
            with suppress(OSError):  # PermissionError where not permitted
                os.sched_setscheduler(0, os.SCHED_RR, os.sched_param(priority))  # this thread
                return "real-time"
    with suppress(OSError):
        os.setpriority(os.PRIO_PROCESS, 0, NICE)
        return f"nice {NICE}"
    return ""


@contextmanager
def ordinary() -> Iterator[None]:
    """Run the calling thread at the ordinary priority inside the block (long CPU work, such as
    a warm-up's renders, that must not take a core from the designer's programs), then at the
    one it had."""
    if not hasattr(os, "sched_getscheduler"):
        yield
        return
    policy, param = os.sched_getscheduler(0), os.sched_getparam(0)
    nice = os.getpriority(os.PRIO_PROCESS, 0)
    with suppress(OSError):
        os.sched_setscheduler(0, os.SCHED_OTHER, os.sched_param(0))
        os.setpriority(os.PRIO_PROCESS, 0, max(nice, 0))
    try:
        yield
    finally:
        with suppress(OSError):
            os.setpriority(os.PRIO_PROCESS, 0, nice)
            os.sched_setscheduler(0, policy, param)
