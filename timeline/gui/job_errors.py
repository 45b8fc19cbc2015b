"""How an error that ends a background job becomes one line for the message bar."""

from __future__ import annotations

import sys
import traceback


def one_line(text: str) -> str:
    """A message on one line: its lines joined by spaces."""
    return " ".join(line.strip() for line in text.splitlines() if line.strip())


def unexpected(what: str, exc: BaseException) -> str:
    """A bug ended a job: its traceback goes to stderr, the user reads what failed and why."""
    traceback.print_exception(exc, file=sys.stderr)
    return one_line(f"{what} failed: {type(exc).__name__}: {exc}")
