"""Coverage-guided fuzzing (atheris/libFuzzer) of the readers, seeded with real files.

Skipped where atheris is not installed (it is a test dependency on Linux, CPython < 3.12).
"""

from __future__ import annotations

import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from .conftest import count, seed_files

pytest.importorskip("atheris")

RUNS = 1000
HARNESS = Path(__file__).with_name("atheris_readers.py")


@pytest.fixture(scope="module")
def seeds(tmp_path_factory):
    return seed_files(tmp_path_factory.mktemp("atheris-seeds"))


@pytest.mark.heavy
@pytest.mark.parametrize("ext", ["htl", "csv", "ahap", "haptic", "wav"])
def test_libfuzzer_finds_no_crash_in_a_reader(seeds, ext, tmp_path):
    if not seeds.get(ext):
        pytest.skip(f"no {ext} seed (the shared corpus is not present)")
    corpus = tmp_path / "corpus"
    corpus.mkdir()
    for i, seed in enumerate(seeds[ext]):
        shutil.copy(seed, corpus / f"seed{i}.{ext}")
    runs = count(RUNS)
    done = subprocess.run(
        [sys.executable, str(HARNESS), ext, f"-runs={runs}", "-seed=1", "-max_len=65536",
         "-rss_limit_mb=4096", "-timeout=60", f"-artifact_prefix={tmp_path}/", str(corpus)],
        capture_output=True, text=True, timeout=600, cwd=Path(__file__).resolve().parents[2],
    )  # fmt: skip
    log = done.stderr
    assert done.returncode == 0, log[-3000:]
    match = re.search(r"Done (\d+) runs", log)
    assert match and int(match.group(1)) >= runs
