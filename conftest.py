"""Test-wide settings: Qt draws offscreen so the suite runs on machines with no display, and
OpenBLAS keeps to one thread as the command line does (timeline.cli.main.one_blas_thread); the
`busy_interpreter` fixture for tests of real time under a held interpreter lock. Hypothesis
has no per-example deadline here: the suite asserts behaviour, never time, and a loaded
machine must not fail a property."""

import os
import sys
import threading
from collections.abc import Callable, Iterator
from contextlib import AbstractContextManager, contextmanager

import pytest
from hypothesis import settings

settings.register_profile("suite", deadline=None)
settings.load_profile("suite")

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # before anything loads numpy
os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
os.environ.setdefault("MPLBACKEND", "Agg")

SLICE_SECONDS = 0.025  # how long the busy thread keeps the interpreter lock once it has it


@contextmanager
def _busy_interpreter() -> Iterator[None]:
    """A thread spinning in Python that hands the interpreter lock over every 25 ms only: the
    GUI holding the lock, as a long paint or scene update does."""
    before = sys.getswitchinterval()
    stop = threading.Event()

    def spin() -> None:
        n = 0
        while not stop.is_set():
            n += 1

    sys.setswitchinterval(SLICE_SECONDS)
    thread = threading.Thread(target=spin, daemon=True, name="busy interpreter")
    thread.start()
    try:
        yield
    finally:
        stop.set()
        thread.join()
        sys.setswitchinterval(before)


@pytest.fixture
def busy_interpreter() -> Callable[[], AbstractContextManager[None]]:
    """`with busy_interpreter():` starves this process's other threads of the lock."""
    return _busy_interpreter
