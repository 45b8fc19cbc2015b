"""Sound-to-haptic analysis: amplitude and frequency envelopes and emphasis from a recording.

Modules, one idea each: settings (what can be tuned, and the defaults), envelope (RMS
follower), spectrum (centroid, flux and onset strength per frame), reduce (breakpoint
reduction), onsets (emphasis), sound (the pipeline), source (reading a sound file in blocks),
staging (a design's level for a device), agreement (measures against a reference design).
Pure numpy/numba; no Qt and no plugin imports. The names below load their module when first
used, so `convert --help` starts without numpy.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:  # what pyright and IDEs see; at run time each name loads on first use
    from timeline.analysis.settings import DEFAULTS, AnalysisSettings
    from timeline.analysis.sound import SoundAnalysis, analyse, analyse_blocks

_HOMES = {
    "DEFAULTS": "settings",
    "AnalysisSettings": "settings",
    "SoundAnalysis": "sound",
    "analyse": "sound",
    "analyse_blocks": "sound",
}

__all__ = [
    "DEFAULTS",
    "AnalysisSettings",
    "SoundAnalysis",
    "analyse",
    "analyse_blocks",
]


def __getattr__(name: str) -> Any:
    if name not in _HOMES:
        raise AttributeError(f"module 'timeline.analysis' has no attribute {name!r}")
    return getattr(importlib.import_module(f"timeline.analysis.{_HOMES[name]}"), name)


def __dir__() -> list[str]:
    """The public names, loaded or not (what an IDE or a notebook completes)."""
    return sorted(__all__)
