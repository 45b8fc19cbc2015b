"""Parsers of untrusted files run in a child process: a crash there is one sentence here."""

import ctypes
import os

import numpy as np
import pytest

from timeline.errors import HapticTimelineError
from timeline.files import crash_isolation
from timeline.plugins.file_formats import FormatError


def crash() -> None:
    ctypes.string_at(0)  # reads address 0: a segmentation fault, as a broken native parser does


def hog() -> np.ndarray:
    return np.ones(2**31)  # 16 GiB, far beyond the limit given below


def refuse() -> None:
    raise FormatError("x.mat holds no numeric vector to import")


def surprise() -> None:
    raise KeyError("header")


def pid_and_square(x: float) -> tuple[int, float]:
    return os.getpid(), x * x


def test_a_result_comes_back_from_another_process():
    pid, value = crash_isolation.run(pid_and_square, 3.0, what="x.mat")
    assert value == 9.0 and pid != os.getpid()


def test_a_segfault_in_the_parser_is_one_sentence():
    with pytest.raises(HapticTimelineError) as info:
        crash_isolation.run(crash, what="broken.mat")
    assert str(info.value) == (
        "broken.mat could not be read: its parser crashed (SIGSEGV); the file is damaged or not "
        "what its name says"
    )


def test_the_memory_limit_holds():
    with pytest.raises(
        HapticTimelineError,
        match=r"huge.mat could not be read: its parser needed more than 1.0 GiB",
    ):
        crash_isolation.run(hog, what="huge.mat", memory_bytes=2**30)


def test_a_format_error_passes_through_as_it_was():
    with pytest.raises(FormatError, match="^x.mat holds no numeric vector to import$"):
        crash_isolation.run(refuse, what="x.mat")


def test_an_unexpected_exception_is_named():
    with pytest.raises(
        HapticTimelineError, match=r"^odd.otio could not be read: KeyError: 'header'$"
    ):
        crash_isolation.run(surprise, what="odd.otio")


class _Unpicklable(FormatError):
    def __reduce__(self):
        raise TypeError("cannot pickle this error")


def refuse_unpicklably() -> None:
    raise _Unpicklable("x.otio has a clip whose gain is not a number")


def lock() -> object:
    import threading

    return threading.Lock()  # pickle cannot carry a lock: TypeError


def test_an_error_that_cannot_be_passed_back_still_says_its_sentence():
    with pytest.raises(HapticTimelineError, match="^x.otio has a clip whose gain is not a number$"):
        crash_isolation.run(refuse_unpicklably, what="x.otio")


def test_a_result_that_cannot_be_passed_back_is_a_sentence_without_the_type_error():
    with pytest.raises(HapticTimelineError) as info:
        crash_isolation.run(lock, what="x.otio")
    assert (
        str(info.value)
        == "x.otio could not be read: it holds data of a kind this program cannot use"
    )
