"""Mutation testing of one module with mutmut, against the tests that exercise it (not in CI).

    python benchmarks/mutation.py mixer|edits|projectfile [--sample DIGITS] [--jobs N] [--keep]

Copies the repository's tracked files to a temporary folder, configures mutmut there (so the
work tree gets no mutants/ folder and no config), runs it on the module with its targeted
tests, and prints the count of each outcome and the surviving mutants (`mutmut show NAME` in the
printed folder, kept with --keep, shows one). `--sample 05` tests only the mutants whose number
ends in 0 or 5 (a fifth of each function's mutants, the same ones every run): the whole of a
module takes about an hour on two cores. Needs mutmut (the `test` extra) on Python 3.11.
"""

from __future__ import annotations

import argparse
import collections
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

# module -> (files to mutate, tests that exercise them)
TARGETS: dict[str, tuple[list[str], list[str]]] = {
    "mixer": (
        ["timeline/rendering/mixer.py"],
        [
            "tests/core/test_mixer_cache.py",
            "tests/core/test_mixer_behaviour.py",
            "tests/core/test_exact_placement.py",
            "tests/stability/test_mixer_incremental.py",
            "tests/stability/test_mixer_threads.py",
            "tests/stability/test_window_clips.py",
        ],
    ),
    "edits": (
        ["timeline/edits/*"],
        [
            "tests/core/test_edit_properties.py",
            "tests/core/test_edit_scale.py",
            "tests/core/test_tile_edits.py",
            "tests/core/test_placement.py",
            "tests/core/test_edits_behaviour.py",
            "tests/core/test_merge_placement.py",
            "tests/core/test_markers.py",
            "tests/core/test_step_names.py",
            "tests/core/test_tile_params.py",
            "tests/core/test_vibration.py",
            "tests/core/test_context_track.py",
            "tests/core/test_tile_shape_behaviour.py",
            "tests/core/test_edits_more_behaviour.py",
            "tests/core/test_step_names_more.py",
            "tests/core/test_vibration_behaviour.py",
            "tests/core/test_clip_trim_behaviour.py",
            "tests/core/test_step_history_behaviour.py",
        ],  # fmt: skip
    ),
    "projectfile": (
        ["timeline/files/projectfile.py", "timeline/files/project_fields.py"],
        [
            "tests/core/test_projectfile.py",
            "tests/core/test_projectfile_bytes.py",
            "tests/core/test_old_schemas.py",
            "tests/core/test_projectfile_roundtrip.py",
            "tests/core/test_projectfile_messages.py",
            "tests/core/test_hostile_projects.py",
        ],  # fmt: skip
    ),
}


def config(files: list[str], tests: list[str]) -> str:
    """The [mutmut] section of setup.cfg for these files and tests."""
    tests = [t for t in tests if (ROOT / t).exists()]
    lines = ["[mutmut]", "source_paths = timeline", "only_mutate ="]
    lines += [f"    {f}" for f in files]
    lines += ["also_copy =", "    tracks", "    device", "    importers", "    projects"]
    lines += ["pytest_add_cli_args_test_selection ="] + [f"    {t}" for t in tests]
    lines += ["pytest_add_cli_args =", "    -p", "    no:cacheprovider", "    -q"]
    return "\n".join(lines) + "\n"


def copy_tree(target: Path) -> None:
    """The repository's tracked files (as on disk) under target."""
    listed = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, check=True,
                            capture_output=True).stdout.decode().split("\0")  # fmt: skip
    for name in filter(None, listed):
        source = ROOT / name
        if source.is_file():
            (target / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(source, target / name)


def outcomes(folder: Path, env: dict[str, str]) -> collections.Counter[str]:
    """Count of each mutant outcome, printing the ones that were not killed."""
    shown = subprocess.run([sys.executable, "-m", "mutmut", "results", "--all", "true"],
                           cwd=folder, env=env, capture_output=True, text=True).stdout  # fmt: skip
    counts: collections.Counter[str] = collections.Counter()
    for line in shown.splitlines():
        name, _, status = line.strip().rpartition(": ")
        if name and status != "not checked":
            counts[status] += 1
            if status != "killed":
                print(f"  {status}: {name}")
    return counts


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("module", choices=sorted(TARGETS))
    parser.add_argument("--jobs", type=int, default=2, help="mutants tested at once")
    parser.add_argument("--keep", action="store_true", help="keep the temporary folder")
    parser.add_argument("--sample", default="", help="last digits of the mutants to test")
    args = parser.parse_args()
    files, tests = TARGETS[args.module]
    folder = Path(tempfile.mkdtemp(prefix=f"mutation-{args.module}-"))
    try:
        copy_tree(folder)
        (folder / "setup.cfg").write_text(config(files, tests))
        env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
        env["QT_QPA_PLATFORM"] = "offscreen"
        run = [sys.executable, "-m", "mutmut", "run", "--max-children", str(args.jobs)]
        run += [f"*__mutmut_*{digit}" for digit in args.sample]
        subprocess.run(run, cwd=folder, env=env, check=False, stdout=subprocess.DEVNULL)
        counts = outcomes(folder, env)
        killed, total = counts["killed"] + counts["timeout"], sum(counts.values())
        print(f"{args.module}: {dict(counts)}; killed {killed} of {total} "
              f"({100 * killed / max(total, 1):.1f} %)")  # fmt: skip
        if args.keep:
            print(f"kept in {folder}")
        return 0
    finally:
        if not args.keep:
            shutil.rmtree(folder, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
