"""Every reader, fed mutations of real files, returns a result or one sentence: never a crash.

Seeds are real files of each format (corpus .haptic/.ahap/.wav, our example projects, small
files from our writers and soundfile for the rest); each example applies up to six mutations.
A parse that succeeds must give data a project can hold (finite numbers, savable).
"""

from __future__ import annotations

import math

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from timeline.errors import HapticTimelineError, ProjectFileError
from timeline.files import projectfile
from timeline.files.importing import place, read_file

from .conftest import count, example_project, seed_files
from .mutate import mutations

# Examples per format. .mat and .otio parse in a child interpreter (~1 s each), so fewer.
EXAMPLES = {"mat": 6, "otio": 6, "htl": 200}
DEFAULT_EXAMPLES = 60
SETTINGS = {
    "deadline": None,
    "database": None,
    "suppress_health_check": [HealthCheck.too_slow, HealthCheck.data_too_large],
}


@pytest.fixture(scope="module")
def seeds(tmp_path_factory):
    return seed_files(tmp_path_factory.mktemp("seeds"))


def _check_import(path) -> None:
    try:
        imported = read_file(path)
    except HapticTimelineError as exc:
        assert str(exc) and "\n" not in str(exc)
        return
    try:
        project, _ = place(example_project(), imported)
    except HapticTimelineError as exc:  # e.g. a clip the project cannot hold
        assert "\n" not in str(exc)
        return
    assert math.isfinite(project.duration)
    projectfile.dumps(project)  # strict JSON: no NaN or inf got in


@pytest.mark.parametrize(
    "ext", ["htl", "ahap", "haptic", "wav", "flac", "aiff", "csv", "mat", "otio"]
)
def test_mutated_files_of_each_format_read_cleanly(seeds, ext, tmp_path):
    if ext not in seeds or not seeds[ext]:
        pytest.skip(f"no {ext} seed (the shared corpus is not present)")
    files = [p.read_bytes() for p in seeds[ext]]
    n = count(EXAMPLES.get(ext, DEFAULT_EXAMPLES))
    target = tmp_path / f"fuzzed.{ext}"

    @settings(max_examples=n, **SETTINGS)
    @given(st.sampled_from(files).flatmap(mutations))
    def run(data: bytes) -> None:
        if ext == "htl":
            try:
                project = projectfile.loads(data)
            except ProjectFileError as exc:
                assert "\n" not in str(exc)
                return
            assert math.isfinite(project.duration)
            projectfile.dumps(project)
            return
        target.write_bytes(data)
        _check_import(target)

    run()
