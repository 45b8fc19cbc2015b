"""The playing threads' priority: where neither real time nor a higher priority is permitted,
a short slice (Linux 6.12 on), which anyone may ask for."""

from __future__ import annotations

import platform
import sys
import threading

import pytest

from timeline.plugins.device_protocol.child_process import (
    PRIORITY_ENV,
    SLICE_SECONDS,
    prefer_real_time,
)


def _eevdf_slices() -> bool:
    if not sys.platform.startswith("linux"):
        return False
    major, minor = (int(x) for x in platform.release().split(".")[:2])
    return (major, minor) >= (6, 12)


def _asked() -> tuple[str, int]:
    """What prefer_real_time granted a fresh thread, and that thread's slice (ns)."""
    got: list = []

    def run() -> None:
        got.append(prefer_real_time())
        with open("/proc/thread-self/sched", encoding="ascii") as sched:
            got.append(next(int(line.split()[-1]) for line in sched if "se.slice" in line))

    thread = threading.Thread(target=run)
    thread.start()
    thread.join()
    return got[0], got[1]


@pytest.mark.skipif(not _eevdf_slices(), reason="a task's own slice needs Linux 6.12 or later")
def test_an_ordinary_playing_thread_asks_for_a_short_slice(monkeypatch):
    monkeypatch.setenv(PRIORITY_ENV, "off")
    _, default = _asked()
    monkeypatch.setenv(PRIORITY_ENV, "normal")  # as a user without rtprio or CAP_SYS_NICE
    granted, ns = _asked()
    assert granted == "short slice"
    assert ns == round(SLICE_SECONDS * 1e9) == 500_000 and default > ns
