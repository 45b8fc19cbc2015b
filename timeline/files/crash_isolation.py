"""Run a parser of untrusted files in a child process, so that its crash is one sentence.

Some parsers are native code that a damaged file can crash (scipy's .mat reader and
opentimelineio have been seen to end in a segmentation fault). `run` calls such a parser in a
fresh interpreter (`python -m timeline.files.crash_isolation`, so a user's script is never
re-run the way multiprocessing re-imports __main__) under a memory limit (RLIMIT_AS) and a time
limit; a signal, a limit or an unexpected exception in the child becomes a HapticTimelineError
naming the file, and the editor or CLI carries on. The function goes by name (found on the parent's
sys.path), its arguments and result by pickle over the child's stdin and stdout.
"""

from __future__ import annotations

import importlib
import os
import pickle
import signal
import subprocess
import sys
from collections.abc import Callable
from typing import Any

from timeline.errors import HapticTimelineError, SandboxError
from timeline.signal import memory

SECONDS = 120.0  # wall-clock limit for one parse
MIN_MEMORY = 2 * 2**30  # the child may always use this much address space ...
MAX_MEMORY = 32 * 2**30  # ... and never more than this (or what the machine has free)


def run(
    fn: Callable[..., Any],
    *args: Any,
    what: str,
    seconds: float = SECONDS,
    memory_bytes: int | None = None,
) -> Any:
    """fn(*args) computed in a child process; its result, or one sentence if that fails.

    fn must be a module-level function. A HapticTimelineError raised by fn is re-raised as it
    was; anything else that goes wrong is a SandboxError "WHAT could not be read: ...".
    """
    limit = memory_bytes or _memory_limit()
    request = pickle.dumps((sys.path, fn.__module__, fn.__qualname__, args, limit))
    try:
        done = subprocess.run(
            [sys.executable, "-m", __name__],
            input=request,
            capture_output=True,
            timeout=seconds,
            check=False,
        )
    except subprocess.TimeoutExpired:
        raise SandboxError(
            f"{what} could not be read: its parser took longer than {seconds:g} s"
        ) from None
    try:
        status, payload = pickle.loads(done.stdout)
    except Exception:  # noqa: BLE001 - no answer: the child died before it could send one
        raise SandboxError(f"{what} could not be read: {_death(done.returncode)}") from None
    if status == "ok":
        return payload
    if status == "raise":
        raise payload
    raise SandboxError(f"{what} could not be read: {payload}")


def _memory_limit() -> int:
    free = memory.available_bytes()
    if free is None:
        return MAX_MEMORY
    return int(max(MIN_MEMORY, min(MAX_MEMORY, memory.HEADROOM * free)))


def _death(returncode: int) -> str:
    if returncode < 0:
        try:
            name = signal.Signals(-returncode).name
        except ValueError:
            name = f"signal {-returncode}"
        return f"its parser crashed ({name}); the file is damaged or not what its name says"
    return f"its parser stopped unexpectedly (exit code {returncode})"


def _limit_memory(limit: int) -> None:
    import resource

    try:
        _, hard = resource.getrlimit(resource.RLIMIT_AS)
        if hard == resource.RLIM_INFINITY or limit < hard:
            resource.setrlimit(resource.RLIMIT_AS, (limit, hard))
    except (ValueError, OSError):
        pass  # a platform without address-space limits still gets the crash isolation


def _serve(stdin: Any, stdout: Any) -> None:
    """The child: read a request, call the function, write ("ok"|"raise"|"fail", payload)."""
    path, module, name, args, limit = pickle.loads(stdin.read())
    sys.path[:] = path  # find fn's module where the parent found it
    _limit_memory(limit)
    try:
        fn = getattr(importlib.import_module(module), name)
        message: tuple[str, Any] = ("ok", fn(*args))
    except HapticTimelineError as exc:
        message = ("raise", exc)
    except MemoryError:
        message = ("fail", f"its parser needed more than {memory.size_text(limit)} of memory")
    except Exception as exc:  # noqa: BLE001 - any parser failure becomes one sentence
        text = str(exc).splitlines()[0][:160] if str(exc) else ""
        message = ("fail", f"{type(exc).__name__}{': ' + text if text else ''}")
    stdout.write(_answer(message, limit))
    stdout.flush()


def _answer(message: tuple[str, Any], limit: int) -> bytes:
    """The message pickled so the parent can load it; else the same outcome in plain words."""
    status, payload = message
    try:
        data = pickle.dumps(message)
        if status == "raise":
            pickle.loads(data)  # an error the parent could not rebuild would read as a crash
        return data
    except MemoryError:
        return pickle.dumps(
            ("fail", f"its parser needed more than {memory.size_text(limit)} of memory")
        )
    except Exception:  # noqa: BLE001 - a value pickle cannot carry
        if status == "raise":  # the user's sentence, as the error every caller catches
            return pickle.dumps(("raise", HapticTimelineError(str(payload))))
        return pickle.dumps(("fail", "it holds data of a kind this program cannot use"))


if __name__ == "__main__":
    answer = os.fdopen(os.dup(1), "wb")
    os.dup2(2, 1)  # whatever the parser prints goes to stderr, never into the answer
    _serve(sys.stdin.buffer, answer)
