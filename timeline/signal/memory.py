"""Memory bounds: refuse work that would not fit, saying how much it would need.

A render or import that asks for more memory than the machine has would otherwise end in a
MemoryError (or the kernel killing the process) after minutes of work; checking first turns it
into one sentence with the size, before anything is done.
"""

from __future__ import annotations

import os

from timeline.errors import HapticTimelineError

HEADROOM = 0.8  # use at most this share of the memory available now
CHECK_ABOVE = 256 * 2**20  # smaller requests are not checked (reading /proc costs ~0.1 ms)


def available_bytes() -> int | None:
    """Memory a new allocation can have now: free memory, less if an address-space limit binds."""
    free = _free_memory()
    limit = _address_space_left()
    if free is None or limit is None:
        return free if limit is None else limit
    return min(free, limit)


def _address_space_left() -> int | None:
    """What `ulimit -v` (RLIMIT_AS) still allows this process, or None without a limit."""
    try:
        import resource

        soft, _ = resource.getrlimit(resource.RLIMIT_AS)
        if soft == resource.RLIM_INFINITY:
            return None
        with open("/proc/self/statm", encoding="ascii") as f:
            used = int(f.read().split()[0]) * os.sysconf("SC_PAGE_SIZE")
    except (ImportError, OSError, ValueError, IndexError):
        return None
    return max(0, soft - used)


def _free_memory() -> int | None:
    """MemAvailable on Linux, else free physical pages, else None."""
    try:
        with open("/proc/meminfo", encoding="ascii") as f:
            for line in f:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        pass
    try:
        return os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")
    except (ValueError, OSError, AttributeError):
        return None


def size_text(nbytes: float) -> str:
    """A byte count for people: 11.2 GiB, 340 MiB."""
    for unit, scale in (("GiB", 2**30), ("MiB", 2**20), ("KiB", 2**10)):
        if nbytes >= scale:
            return f"{nbytes / scale:.1f} {unit}"
    return f"{int(nbytes)} bytes"


def count_text(n: int) -> str:
    """A sample count for people: in full up to 15 digits, beyond that as 3.2e+303."""
    return str(n) if n < 10**15 else f"{n:.3g}"


def require(nbytes: float, what: str, hint: str = "") -> None:
    """Raise one sentence if `what` would need more than the memory available now."""
    if nbytes < CHECK_ABOVE:
        return
    free = available_bytes()
    if free is not None and nbytes > HEADROOM * free:
        raise HapticTimelineError(
            f"{what} would need about {size_text(nbytes)} of memory, but only "
            f"{size_text(free)} is available" + (f"; {hint}" if hint else "")
        )
