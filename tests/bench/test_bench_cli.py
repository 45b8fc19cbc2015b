"""`haptic-timeline bench --quick` runs every benchmark, prints its tables and writes its plots."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

from timeline.cli.main import main

PLOTS = ("mixer_speed", "quality_pareto", "resampler", "sim_integrators", "sim_speed", "scale")
TITLES = ("Example projects:", "Mixer:", "Quality presets overall", "Resamplers:", "Integrators:",
          "Simulated knob:", "Accumulation against math.fsum", "Edit-to-feel latency",
          "Scale: full render", "Scale: building through edits", "Scale: project save",
          "Scale: peak pyramid", "Scale: start-up CPU", "Vibration formats:", "AHAP reader:",
          "Square, saw and triangle waves", "Drag a design with its emphasis",
          "A 1-minute float32 recording", "compare: wall s",
          "convert of a 16-bit mono WAV", "Readers: time against input size")  # fmt: skip


# The editor's own benchmarks start editor processes for a minute or more; CI runs them in quick
# mode on their own (.ci/run), so the suite stays under its four minutes.
EDITOR_BENCHMARKS = ("editor", "playback")


@pytest.mark.heavy
def test_quick_bench_prints_tables_and_writes_plots(tmp_path: Path) -> None:
    from timeline.bench import MODULES

    out = tmp_path / "results"
    chosen = [name for name in MODULES if name not in EDITOR_BENCHMARKS]
    done = subprocess.run(
        [sys.executable, "-m", "timeline.cli.main", "bench", "--quick", "--out", str(out), *chosen],
        capture_output=True, text=True, timeout=300,
    )  # fmt: skip
    assert done.returncode == 0, done.stderr
    for title in TITLES:
        assert f"## {title}" in done.stdout
    assert done.stdout.count("target:") >= 4  # mixer (2), sim speed, edit-to-feel
    tables = (out / "tables.md").read_text()
    assert all(f"## {title}" in tables for title in TITLES)
    assert re.search(r"\|\s*fan_knob\.htl\s*\|\s*position\s*\|\s*84000\s*\|", tables)
    for name in PLOTS:
        png = out / f"{name}.png"
        assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 10_000


def test_unknown_benchmark_is_one_sentence(capsys) -> None:
    assert main(["bench", "--quick", "nonsense"]) == 1
    err = capsys.readouterr().err.strip()
    assert err.startswith("haptic-timeline: there is no benchmark 'nonsense'") and "\n" not in err


def test_list_names_every_benchmark(capsys) -> None:
    assert main(["bench", "--list"]) == 0
    names = [line.split()[0] for line in capsys.readouterr().out.splitlines()]
    assert names == ["examples", "mixer", "quality", "resampler", "integrators", "sim-speed",
                     "estimator", "accumulation", "edit-to-feel", "scale", "convert",
                     "formats", "ahap-reader", "waves", "design-drag", "media", "autosave",
                     "compare", "convert-memory", "readers", "playback", "editor"]  # fmt: skip


def test_each_benchmark_module_is_named_as_listed() -> None:
    from timeline.bench import MODULES, benchmarks

    assert {name: module.NAME for name, module in benchmarks().items()} == {n: n for n in MODULES}


def test_running_one_benchmark_loads_only_its_module(tmp_path: Path) -> None:
    probe = (
        "import sys; from timeline.cli.main import main; "
        f"main(['bench', '--quick', 'waves', '--out', {str(tmp_path)!r}]); "
        "print(sorted(m for m in sys.modules if m.startswith('timeline.bench.')))"
    )
    done = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True)
    assert (
        done.stdout.strip().splitlines()[-1] == "['timeline.bench.report', 'timeline.bench.waves']"
    )
