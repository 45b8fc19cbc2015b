"""An AHAP of 440,000 transients (the issue's 58 MB file, under the 64 MB size cap) is refused
by the documented entry limit with one sentence, before any clip is built, in bounded memory;
a file over the size cap is refused by its size before it is read."""

from __future__ import annotations

import tracemalloc
from pathlib import Path

import pytest

from importers import _vibration as vib
from importers.ahap import MAX_EVENTS
from timeline.cli import main as cli
from timeline.files import importing
from timeline.files.projectfile import load, save

from .conftest import example_project

TRANSIENTS = 440_000
ENTRY = (
    '{"Event":{"Time":%r,"EventType":"HapticTransient",'
    '"EventParameters":[{"ParameterID":"HapticIntensity","ParameterValue":0.8}]}}'
)


def _transients(path: Path, count: int) -> Path:
    entries = ",".join(ENTRY % round(i * 1e-3, 6) for i in range(count))
    path.write_text('{"Version":1.0,"Pattern":[' + entries + "]}")
    return path


@pytest.fixture(scope="module")
def huge_ahap(tmp_path_factory) -> Path:
    path = _transients(tmp_path_factory.mktemp("huge") / "transients.ahap", TRANSIENTS)
    assert 50 * 2**20 < path.stat().st_size < vib.MAX_JSON_BYTES  # 55 MB: read, then refused
    return path


@pytest.mark.heavy
def test_440000_transients_are_refused_in_one_sentence_without_placing_clips(
    huge_ahap, monkeypatch
) -> None:
    placed = []
    real_place = importing.place
    monkeypatch.setattr(importing, "place", lambda *a, **k: placed.append(1) or real_place(*a, **k))
    tracemalloc.start()
    try:
        with pytest.raises(importing.FormatError) as refused:
            importing.import_file(example_project(), huge_ahap)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert str(refused.value) == (
        f"transients.ahap has 440,000 pattern entries; at most {MAX_EVENTS:,} are read"
    )
    assert placed == []  # refused while reading: no tile, placement or clip was made
    # The entries are counted with each object dropped as it is read: the file's bytes and its
    # text are the cost (measured 2.4x the file; parsing it whole was 8.2x, 472 MB for 55 MB).
    assert peak < 3 * huge_ahap.stat().st_size


def test_the_cli_refuses_one_entry_over_the_limit_and_keeps_the_project(tmp_path, capsys) -> None:
    """The CLI's refusal path, on the smallest file the limit refuses (6 MB, not 55: the
    440,000-entry refusal itself is the test above)."""
    over = _transients(tmp_path / "transients.ahap", MAX_EVENTS + 1)
    project = tmp_path / "keep.htl"
    save(example_project(), project)
    before = project.read_bytes()
    assert cli.main(["import", "--into", str(project), str(over)]) != 0
    err = capsys.readouterr().err.strip()
    assert "\n" not in err
    assert f"has {MAX_EVENTS + 1:,} pattern entries; at most {MAX_EVENTS:,} are read" in err
    assert project.read_bytes() == before and load(project).tracks == example_project().tracks
