"""The editor: a PySide6 view over the Qt-free model; every change goes through timeline.edits."""

from __future__ import annotations

import ctypes
import sys

# PySide6 6.12 on Python 3.11 returns None (and True/False) from methods without a new
# reference, so each call takes one away; after some tens of thousands of calls the interpreter
# aborts ("none_dealloc"). On 3.12+ these objects are immortal. Until PySide6 is fixed (or
# pinned), give them reference counts no session can use up.
if sys.version_info < (3, 12):
    for _constant in (None, True, False):
        ctypes.c_ssize_t.from_address(id(_constant)).value += 1 << 40
