"""Benchmarks of speed against accuracy: mixer, quality presets, resamplers, simulator, extremes.

Each module has NAME, SUMMARY and run(quick, out) -> list[Table]; it prints nothing itself and
writes its plots (PNG) into `out`. `haptic-timeline bench` runs them; benchmarks/*.py are thin
scripts over the same modules.
"""

from __future__ import annotations

import importlib
from types import ModuleType

from timeline.plugins import discovery

# Running order by name; plugins' benchmarks (the `haptic_timeline.benchmarks` entry point group,
# e.g. the simulated knob's) take their place in it, and any not named here run last by name.
ORDER = (
    "examples", "mixer", "quality", "resampler", "integrators", "sim-speed", "estimator",
    "accumulation", "edit-to-feel", "scale", "convert", "formats", "ahap-reader", "waves",
    "design-drag", "media", "autosave", "compare", "convert-memory", "readers", "playback",
    "editor",
)  # fmt: skip

BUILT_IN = {
    "examples": "timeline.bench.examples",
    "mixer": "timeline.bench.mixer_speed",
    "quality": "timeline.bench.quality_presets",
    "resampler": "timeline.bench.resampler",
    "accumulation": "timeline.bench.accumulation",
    "edit-to-feel": "timeline.bench.edit_to_feel",
    "scale": "timeline.bench.scale",
    "convert": "timeline.bench.convert",
    "formats": "timeline.bench.formats",
    "ahap-reader": "timeline.bench.ahap_reader",
    "waves": "timeline.bench.waves",
    "design-drag": "timeline.bench.design_drag",
    "media": "timeline.bench.project_media",
    "autosave": "timeline.bench.autosave_journal",
    "compare": "timeline.bench.compare_icons",
    "convert-memory": "timeline.bench.convert_memory",
    "readers": "timeline.bench.readers",
    "playback": "timeline.bench.playback",
    "editor": "timeline.bench.editor",
}


def _registry() -> dict[str, str]:
    """Benchmark name -> module, built-in and registered by plugins, in running order."""
    found = {**discovery.names(discovery.BENCHMARKS), **BUILT_IN}
    order = [n for n in ORDER if n in found] + sorted(set(found) - set(ORDER))
    return {name: found[name] for name in order}


MODULES = _registry()


def benchmarks(names: list[str] | None = None) -> dict[str, ModuleType]:
    """Benchmark name -> module, in running order: all, or only `names` (the other modules, and
    what they import, stay unloaded)."""
    chosen = list(MODULES) if not names else [n for n in MODULES if n in names]
    return {name: importlib.import_module(MODULES[name]) for name in chosen}
