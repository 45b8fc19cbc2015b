"""Atheris (libFuzzer) harness for the readers: `python atheris_readers.py EXT [libFuzzer args]`.

Run by test_atheris.py in a child process, since libFuzzer ends the process when it is done.
Our own parsing code is instrumented for coverage, so the mutations steer into new branches of
the project-file and importer code. Any exception other than one sentence is a crash.
"""

from __future__ import annotations

import os
import sys
import tempfile
from pathlib import Path

import atheris

with atheris.instrument_imports(include=["timeline", "importers"]):
    from timeline.errors import HapticTimelineError
    from timeline.files import projectfile
    from timeline.files.importing import read_file

EXT = sys.argv.pop(1)
TARGET = Path(tempfile.mkdtemp()) / f"fuzzed.{EXT}"


def one_input(data: bytes) -> None:
    """Parse data as a file of EXT: a result or one HapticTimelineError sentence, nothing else."""
    try:
        if EXT == "htl":
            project = projectfile.loads(data)
            projectfile.dumps(project)
        else:
            TARGET.write_bytes(data)
            read_file(TARGET)
    except HapticTimelineError as exc:
        if "\n" in str(exc):
            raise AssertionError(f"a reader's error spans lines: {exc!r}") from None


if __name__ == "__main__":
    os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
    atheris.Setup(sys.argv, one_input)
    atheris.Fuzz()
