"""Start-up: the command line loads heavy libraries only for the verbs that use them."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

PROJECTS = Path(__file__).resolve().parents[2] / "projects"
HEAVY = ("numpy", "scipy", "scipy.interpolate", "scipy.linalg", "matplotlib", "numba", "PySide6",
         "soundfile", "opentimelineio")  # fmt: skip

PROBE = """
import json, sys
from timeline.cli.main import main
try:
    code = main(sys.argv[1:])
except SystemExit as exc:  # --help
    code = exc.code
heavy = {heavy!r}
print(json.dumps([code, sorted(m for m in heavy if m in sys.modules)]))
"""


def _loaded(*argv: str) -> tuple[int, list[str]]:
    """Exit code of a verb and the heavy libraries loaded by the time it returned."""
    done = subprocess.run(
        [sys.executable, "-c", PROBE.format(heavy=HEAVY), *argv],
        capture_output=True,
        text=True,
        check=False,
    )
    code, loaded = json.loads(done.stdout.strip().splitlines()[-1])
    return code, loaded


def test_help_loads_no_heavy_library():
    assert _loaded("--help") == (0, [])


def test_each_verbs_help_loads_no_heavy_library():
    from timeline.cli.main import VERBS

    for verb in VERBS:  # every verb, including ones added later
        assert _loaded(verb, "--help")[1] == [], verb


def test_rendering_an_example_loads_neither_plotting_gui_nor_compiler(tmp_path):
    out = tmp_path / "out.csv"
    code, loaded = _loaded("render", str(PROJECTS / "rising_resistance.htl"), "-o", str(out))
    assert code == 0 and out.stat().st_size > 0
    assert "numpy" in loaded
    # the mixer needs neither scipy's splines nor its BLAS; plotting, the GUI and the compiled
    # sim loop load only for the verbs that use them
    assert not {"matplotlib", "numba", "PySide6", "scipy.interpolate", "scipy.linalg"} & set(loaded)
    # writing CSV loads the CSV format plugin (named after the extension) and no other: not the
    # audio one before it in name order (soundfile), nor .mat (scipy.io) or OTIO after it
    assert not {"scipy", "opentimelineio", "soundfile"} & set(loaded)


def test_each_verb_module_defines_the_verb_it_is_named_for():
    from timeline.cli.main import VERBS, build_parser

    parser = build_parser()
    assert set(parser._subparsers._group_actions[0].choices) == set(VERBS)
    for verb in VERBS:
        alone = build_parser(verb)._subparsers._group_actions[0].choices
        assert list(alone) == [verb]


BLAS_PROBE = """
import ctypes, sys
from timeline.cli.main import main
main(["info", sys.argv[1]])
import numpy, scipy.linalg  # numpy's and scipy's own OpenBLAS builds
counts = []
for path in sorted({line.split()[-1] for line in open("/proc/self/maps") if "openblas" in line}):
    lib = ctypes.CDLL(path)
    for name in ("scipy_openblas_get_num_threads64_", "scipy_openblas_get_num_threads"):
        if hasattr(lib, name):
            counts.append(getattr(lib, name)())
print(counts)
"""


@pytest.mark.skipif(not Path("/proc/self/maps").exists(), reason="reads the loaded libraries")
def test_the_command_line_holds_openblas_to_one_thread_unless_told_otherwise():
    example = str(PROJECTS / "rising_resistance.htl")

    def threads(**env: str) -> list[int]:
        clean = {k: v for k, v in os.environ.items() if k != "OPENBLAS_NUM_THREADS"}
        argv = [sys.executable, "-c", BLAS_PROBE, example]
        done = subprocess.run(argv, capture_output=True, text=True, env={**clean, **env})
        return json.loads(done.stdout.strip().splitlines()[-1])

    assert threads() == [1, 1]  # numpy's and scipy's
    assert threads(OPENBLAS_NUM_THREADS="2") == [2, 2]
