"""Compile the C firmware with the system C compiler, once per source version.

The shared library (the firmware with the host port's HAL) lands in the temporary folder under
a name keyed by a hash of the sources and flags, so a test session, the stream's own process and
the next run reuse it; it is written under a temporary name and renamed, so two processes
building at once never load half a file. The sanitizer build (AddressSanitizer and UBSan) is a
small executable instead (fuzz_main.c): a sanitized library cannot be loaded into a Python that
was not started with its runtime.
"""

from __future__ import annotations

import hashlib
import os
import shutil
import subprocess
import tempfile
from pathlib import Path

from timeline.errors import HapticTimelineError

HERE = Path(__file__).resolve().parent
CORE = ("ht_fw.c",)
SIM = ("ports/sim/ht_sim.c",)
HEADERS = ("ht_fw.h", "ht_hal.h")
# Strict C99; no contraction into fused multiply-adds, so the loop's arithmetic is the sim's.
WARNINGS = ("-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic")
FLAGS = (*WARNINGS, "-O2", "-ffp-contract=off", "-DHT_TRACE")
SANITIZE = ("-fsanitize=address,undefined", "-fno-sanitize-recover=all", "-g", "-O1")


class BuildError(HapticTimelineError):
    """The firmware could not be compiled (no C compiler, or it refused the sources)."""


def compiler() -> str:
    """The C compiler: $CC, else cc; BuildError when there is none."""
    name = os.environ.get("CC", "cc")
    found = shutil.which(name)
    if found is None:
        raise BuildError(
            f"no C compiler {name!r} was found to build the knob's firmware "
            "(apt-get install build-essential)"
        )
    return found


def _key(sources: tuple[str, ...], flags: tuple[str, ...]) -> str:
    digest = hashlib.sha256(" ".join(flags).encode())
    for name in (*sources, *HEADERS):
        digest.update((HERE / name).read_bytes())
    return digest.hexdigest()[:16]


def _build(sources: tuple[str, ...], flags: tuple[str, ...], name: str) -> Path:
    target = Path(tempfile.gettempdir()) / f"haptic-timeline-firmware-{_key(sources, flags)}" / name
    if target.exists():
        return target
    target.parent.mkdir(parents=True, exist_ok=True)
    partial = target.with_name(f"{name}.{os.getpid()}.part")
    command = [compiler(), *flags, "-o", str(partial), *(str(HERE / s) for s in sources), "-lm"]
    done = subprocess.run(command, capture_output=True, text=True, check=False)
    if done.returncode:
        raise BuildError(f"the knob's firmware did not compile: {done.stderr.strip()[:2000]}")
    os.replace(partial, target)
    return target


def shared_library() -> Path:
    """The firmware and the host port as a shared library (built on first use)."""
    return _build((*CORE, *SIM), (*FLAGS, "-fPIC", "-shared"), "libhtfw.so")


def sanitized_harness() -> Path:
    """The fuzzing harness (ports/sim/fuzz_main.c) under AddressSanitizer and UBSan."""
    flags = (*WARNINGS, *SANITIZE, "-ffp-contract=off", "-DHT_TRACE")
    return _build((*CORE, *SIM, "ports/sim/fuzz_main.c"), flags, "ht_fuzz")
