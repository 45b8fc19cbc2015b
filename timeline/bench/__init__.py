"""Benchmarks of speed against accuracy: mixer, quality presets, resamplers, simulator, extremes.

Each module has NAME, SUMMARY and run(quick, out) -> list[Table]; it prints nothing itself and
writes its plots (PNG) into `out`. `haptic-timeline bench` runs them; benchmarks/*.py are thin
scripts over the same modules.
"""

from __future__ import annotations

import importlib
from types import ModuleType

MODULES = {  # benchmark name -> module, in running order
    "examples": "timeline.bench.examples",
    "mixer": "timeline.bench.mixer_speed",
    "quality": "timeline.bench.quality_presets",
    "resampler": "timeline.bench.resampler",
    "integrators": "timeline.bench.sim_integrators",
    "sim-speed": "timeline.bench.sim_speed",
    "estimator": "timeline.bench.estimator",
    "accumulation": "timeline.bench.accumulation",
    "edit-to-feel": "timeline.bench.edit_to_feel",
    "scale": "timeline.bench.scale",
    "convert": "timeline.bench.convert",
    "formats": "timeline.bench.formats",
    "waves": "timeline.bench.waves",
    "design-drag": "timeline.bench.design_drag",
}


def benchmarks(names: list[str] | None = None) -> dict[str, ModuleType]:
    """Benchmark name -> module, in running order: all, or only `names` (the other modules, and
    what they import, stay unloaded)."""
    chosen = list(MODULES) if not names else [n for n in MODULES if n in names]
    return {name: importlib.import_module(MODULES[name]) for name in chosen}
