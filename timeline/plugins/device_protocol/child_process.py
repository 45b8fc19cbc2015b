"""Helpers for a process that streams to a device (the USB knob's, the editor's play process):
ending it, and asking the OS to run its playing thread ahead of ordinary programs."""

from __future__ import annotations

import ctypes
import os
import platform
import sys
from collections.abc import Iterator
from contextlib import contextmanager, suppress
from multiprocessing.connection import Connection
from multiprocessing.process import BaseProcess

# "normal": what an unprivileged user gets (the short slice below, no real time, no nice -10);
# "off": nothing asked at all (as before any of this, for comparisons)
PRIORITY_ENV = "HAPTIC_TIMELINE_PLAY_PRIORITY"
REAL_TIME_PRIORITY = 10  # the round-robin real-time priority asked for (1-99; audio uses 5-20)
NICE = -10  # the niceness asked for where real-time scheduling is not permitted
# The slice (EEVDF, Linux 6.12 on) asked for the playing threads at the ordinary priority: a
# thread woken with a shorter slice than the running one's preempts it instead of waiting for
# that slice's end, and is picked first among the threads owed time. Permitted to anyone.
SLICE_SECONDS = 0.0005
_SCHED_SETATTR = {"x86_64": 314, "aarch64": 274}  # the syscall's number by machine


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
    sim's 30 ms lead. Where neither is permitted (or HAPTIC_TIMELINE_PLAY_PRIORITY=normal)
    it asks for a short slice (`short_slice`), which anyone may. Returns what was granted:
    "real-time", "nice -10", "short slice" (with nice -10: "nice -10, short slice") or ""
    (nothing, or HAPTIC_TIMELINE_PLAY_PRIORITY=off)."""
    mode = os.environ.get(PRIORITY_ENV)
    if mode == "off" or not hasattr(os, "sched_setscheduler"):
        return ""
    got = []
    if mode != "normal":
        import resource  # POSIX only, as sched_setscheduler

        limit = resource.getrlimit(resource.RLIMIT_RTPRIO)[0]
        for priority in (REAL_TIME_PRIORITY, min(REAL_TIME_PRIORITY, limit)):
            if priority > 0:
                with suppress(OSError):  # PermissionError where not permitted
                    os.sched_setscheduler(0, os.SCHED_RR, os.sched_param(priority))  # this thread
                    return "real-time"
        with suppress(OSError):
            os.setpriority(os.PRIO_PROCESS, 0, NICE)
            got.append(f"nice {NICE}")
    if short_slice(SLICE_SECONDS):
        got.append("short slice")
    return ", ".join(got)


class _SchedAttr(ctypes.Structure):
    """Linux's struct sched_attr (include/uapi/linux/sched/types.h), its first version."""

    _fields_ = [  # noqa: RUF012 - ctypes reads this class attribute
        ("size", ctypes.c_uint32),
        ("sched_policy", ctypes.c_uint32),
        ("sched_flags", ctypes.c_uint64),
        ("sched_nice", ctypes.c_int32),
        ("sched_priority", ctypes.c_uint32),
        ("sched_runtime", ctypes.c_uint64),
        ("sched_deadline", ctypes.c_uint64),
        ("sched_period", ctypes.c_uint64),
        ("sched_util_min", ctypes.c_uint32),
        ("sched_util_max", ctypes.c_uint32),
    ]


def short_slice(seconds: float) -> bool:
    """Ask that the calling thread (ordinary scheduling, its niceness kept) be run in slices of
    `seconds` (Linux 6.12 on: sched_setattr's runtime sets an EEVDF task's slice; the kernel
    clamps it to 0.1-100 ms). True if the kernel took it; elsewhere (older kernels take the
    call but ignore the runtime), False or a silent no-op."""
    number = _SCHED_SETATTR.get(platform.machine())
    if not sys.platform.startswith("linux") or number is None:
        return False
    attr = _SchedAttr(
        size=ctypes.sizeof(_SchedAttr),
        sched_policy=os.SCHED_OTHER,
        sched_nice=os.getpriority(os.PRIO_PROCESS, 0),
        sched_runtime=round(seconds * 1e9),
    )
    libc = ctypes.CDLL(None, use_errno=True)
    return libc.syscall(number, 0, ctypes.byref(attr), 0) == 0


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
            os.sched_setscheduler(0, policy, param)  # a slice asked for stays (Linux 6.18)
