"""SIGKILL during a save or an autosave: the file is always one complete version, nothing else.

A writer is killed at a random moment while it saves two versions in turn. After every kill
the project file loads and is exactly one of the two versions (nothing lost, never a mix), and
the next save removes the temporary the killed writer left behind.
"""

from __future__ import annotations

import os
import random
import signal
import subprocess
import sys
import textwrap
import time

from timeline import edits
from timeline.files import projectfile
from timeline.files.atomic import PARTIAL, remove_leftovers

from .conftest import count, example_project

KILLS = 30
AUTOSAVE_KILLS = 4


def _versions():
    a = example_project()
    track = a.tracks[0]
    b = edits.move_clip(a, track.clips[0].id, track.clips[0].start + 0.125)
    return projectfile.dumps(a), projectfile.dumps(b), a, b


def _saver(path, a, b) -> int:
    """A forked child that saves a and b in turn until it is killed."""
    pid = os.fork()
    if pid == 0:  # the child: never returns into pytest
        try:
            i = 0
            while True:
                projectfile.save(a if i % 2 else b, path)
                i += 1
        finally:
            os._exit(1)
    return pid


def test_a_kill_during_save_never_loses_or_mixes_a_version(tmp_path):
    text_a, text_b, a, b = _versions()
    path = tmp_path / "design.htl"
    projectfile.save(a, path)
    rng = random.Random(10)
    leftovers = 0
    kills = count(KILLS)
    for _ in range(kills):
        pid = _saver(path, a, b)
        time.sleep(rng.uniform(0.0, 0.08))
        os.kill(pid, signal.SIGKILL)
        os.waitpid(pid, 0)
        assert path.read_text() in (text_a, text_b)  # one whole version, which loads:
        assert projectfile.load(path) in (a, b)
        leftovers += sum(PARTIAL in p.name for p in tmp_path.iterdir())
        projectfile.save(a, path)  # the next save cleans up after the killed writer
        assert [p.name for p in tmp_path.iterdir()] == ["design.htl"]
    assert leftovers > 0  # the kills did land mid-write (else this test proves nothing)


AUTOSAVER = textwrap.dedent(
    """
    import sys
    from PySide6.QtCore import QCoreApplication
    app = QCoreApplication([])
    from timeline import edits
    from timeline.files import projectfile
    from timeline.gui.autosave import Autosaver
    from timeline.gui.document import Document
    doc = Document(projectfile.load(sys.argv[1]))
    saver = Autosaver(doc)
    track = doc.project.tracks[0].id
    tile = next(iter(doc.project.tiles))
    print("ready", flush=True)
    i = 0
    while True:
        i += 1
        doc.apply("add clip", edits.add_clip, track, tile, 1.0 + i)
        saver.save_now()
    """
)


def test_a_kill_during_autosave_always_leaves_a_recoverable_autosave(tmp_path, monkeypatch):
    from timeline.gui import autosave

    monkeypatch.setenv("XDG_DATA_HOME", str(tmp_path / "data"))
    original = example_project()
    source = tmp_path / "design.htl"
    projectfile.save(original, source)
    clips = len(original.tracks[0].clips)
    rng = random.Random(11)
    for _ in range(count(AUTOSAVE_KILLS)):
        child = subprocess.Popen(
            [sys.executable, "-c", AUTOSAVER, str(source)],
            env={**os.environ, "QT_QPA_PLATFORM": "offscreen"},
            stdout=subprocess.PIPE,
        )
        assert child.stdout.readline().strip() == b"ready"
        time.sleep(rng.uniform(0.3, 0.8))
        child.send_signal(signal.SIGKILL)
        child.wait()
        child.stdout.close()
        found = autosave.recoverable()
        assert len(found) == 1  # exactly one autosave, and it loads:
        recovered = found[0].load()
        assert len(recovered.tracks[0].clips) > clips  # the edits made before the kill
        found[0].discard()
        remove_leftovers(autosave.autosave_dir())  # what the next autosave does first
        assert list(autosave.autosave_dir().iterdir()) == []
