"""Ending a process that streams to a device (the USB knob's, the editor's play process)."""

from __future__ import annotations

from contextlib import suppress
from multiprocessing.connection import Connection
from multiprocessing.process import BaseProcess


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
