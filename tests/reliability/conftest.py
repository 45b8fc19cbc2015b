"""The reliability suite (marker `reliability`): fuzzing, kill loops, fault campaigns.

Every test here runs in CI with the bounded counts below; a longer campaign multiplies them:
`RELIABILITY_SCALE=20 pytest -m reliability`. docs/reliability.md lists each test and its count.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pytest
import soundfile as sf

from tests.corpus import DATA, corpus_dir
from timeline.files import projectfile
from timeline.files.exporting import export_project

ROOT = Path(__file__).resolve().parents[2]
PROJECTS = ROOT / "projects"
SCALE = max(1, int(os.environ.get("RELIABILITY_SCALE", "1")))


def count(n: int) -> int:
    """A test's example or loop count, scaled by RELIABILITY_SCALE."""
    return n * SCALE


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    here = Path(__file__).parent
    for item in items:
        if here in Path(str(item.path)).parents:
            item.add_marker(pytest.mark.reliability)


def example_project():
    """A small project with every tile type: generator, spline and sampled."""
    return projectfile.load(PROJECTS / "notification_buzz.htl")


def seed_files(folder: Path) -> dict[str, list[Path]]:
    """Real files of every readable format, to mutate: corpus files where the corpus has them,
    the hand-written .haptic and AHAP files of tests/data, and small files written by our own
    writers or by soundfile for the rest."""
    seeds: dict[str, list[Path]] = {"htl": sorted(PROJECTS.glob("*.htl"))}
    corpus = corpus_dir()
    if corpus is not None:
        seeds["ahap"] = sorted(corpus.rglob("*.ahap"))[:6]
        seeds["haptic"] = sorted(corpus.rglob("*.haptic"), key=lambda p: p.stat().st_size)[:6]
        seeds["wav"] = sorted(corpus.rglob("*.wav"), key=lambda p: p.stat().st_size)[:2]
    for ext in ("ahap", "haptic"):
        seeds.setdefault(ext, []).extend(sorted(DATA.glob(f"*.{ext}")))
    tone = 0.4 * np.sin(2 * np.pi * 40 * np.arange(400) / 8000)
    for ext, subtype in (("flac", "PCM_16"), ("aiff", "PCM_16"), ("wav", "PCM_16")):
        path = folder / f"tone.{ext}"
        sf.write(path, tone, 8000, subtype=subtype)
        seeds.setdefault(ext, []).append(path)
    project = example_project()
    for ext in ("csv", "mat", "otio", "ahap", "haptic"):
        path = folder / f"example.{ext}"
        export_project(project, path)
        seeds.setdefault(ext, []).append(path)
    return seeds
