"""Benchmarks of speed against accuracy: mixer, quality presets, resamplers, simulator, extremes.

Each module has NAME, SUMMARY and run(quick, out) -> list[Table]; it prints nothing itself and
writes its plots (PNG) into `out`. `haptic-timeline bench` runs them; benchmarks/*.py are thin
scripts over the same modules.
"""

from __future__ import annotations

import importlib
from types import ModuleType

MODULES = (
    "timeline.bench.examples",
    "timeline.bench.mixer_speed",
    "timeline.bench.quality_presets",
    "timeline.bench.resampler",
    "timeline.bench.sim_integrators",
    "timeline.bench.sim_speed",
    "timeline.bench.estimator",
    "timeline.bench.accumulation",
    "timeline.bench.edit_to_feel",
    "timeline.bench.scale",
    "timeline.bench.convert",
    "timeline.bench.formats",
    "timeline.bench.waves",
)


def benchmarks() -> dict[str, ModuleType]:
    """Benchmark name -> module, in running order."""
    found = {}
    for path in MODULES:
        module = importlib.import_module(path)
        found[module.NAME] = module
    return found
