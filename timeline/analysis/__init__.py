"""Sound-to-haptic analysis: amplitude and frequency envelopes and emphasis from a recording.

Modules, one idea each: settings (what can be tuned, Meta Haptics Studio's defaults), envelope
(RMS follower), spectrum (centroid and flux per frame), reduce (breakpoint reduction), onsets
(emphasis), sound (the pipeline), source (reading a sound file in blocks). Pure numpy/numba; no
Qt and no plugin imports.
"""

from timeline.analysis.settings import DEFAULTS, AnalysisSettings, SettingsError
from timeline.analysis.sound import AnalysisError, SoundAnalysis, analyse, analyse_blocks

__all__ = [
    "DEFAULTS",
    "AnalysisError",
    "AnalysisSettings",
    "SettingsError",
    "SoundAnalysis",
    "analyse",
    "analyse_blocks",
]
