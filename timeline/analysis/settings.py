"""The settings of the sound-to-haptic analysis.

Every field is a setting of `haptic-timeline convert` and of the editor's analysis panel. The
envelope and spectrum defaults are those of Meta Haptics Studio's open analysis
(facebook/meta-haptics-sdk, interfaces/studio/audio_analysis), so envelopes start where Studio's
would. Five differ, each said in docs/convert.md: emphasis found adaptively (`adaptive`, with
`peak_window` 30 ms; off with peak_window 0.1 s gives Studio's peak picking), `resolution` 50 %
(100 %: Studio's breakpoint budget alone), `ducking` 20 % (Lofelt Studio's; Meta's is 50 %), and
the envelope's tail below `tail_db` expanded by `tail_ratio` (`--tail-ratio 1`: Studio's).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, fields
from typing import Any

from timeline.errors import SettingsError

SLACK_AT_ZERO = 0.1  # the error a resolution of 0 % allows (it falls with the square of 1 - %)


def _setting(default: Any, help: str) -> Any:
    return field(default=default, metadata={"help": help})


@dataclass(frozen=True)
class AnalysisSettings:
    """How a sound becomes amplitude and frequency envelopes and emphasis."""

    # amplitude: a windowed RMS, then an attack/hold/release follower, sampled every update
    rms_window: float = _setting(1e-4, "length of the moving RMS window (s)")
    attack: float = _setting(1e-4, "time the envelope takes to reach 99 % of a rise (s)")
    hold: float = _setting(1.5e-3, "time the envelope holds a peak before it falls (s)")
    release: float = _setting(0.1, "time the envelope takes to fall 99 % of the way (s)")
    update: float = _setting(1e-3, "time between analysed amplitude points (s)")
    tail_db: float = _setting(
        20.0, "the envelope this far below the sound's peak starts to fall faster (dB)"
    )
    tail_ratio: float = _setting(
        2.0, "how much faster the envelope falls below tail_db: 1 not at all, 2 twice (dB/dB)"
    )
    normalize: bool = _setting(False, "scale the sound so its peak is level_db first")
    level_db: float = _setting(0.0, "peak level after normalising (dBFS)")
    gain_db: float = _setting(0.0, "gain applied to the sound when not normalising (dB)")
    # frequency: the spectral centroid below `centroid_lowpass` mapped from a Hz range to 0..1
    fft_size: int = _setting(1024, "samples per spectrum frame (a power of two)")
    overlap: int = _setting(8, "spectrum frames per frame length (hop = fft_size / overlap)")
    centroid_lowpass: float = _setting(1000.0, "highest frequency the centroid looks at (Hz)")
    frequency_min: float = _setting(30.0, "centroid mapped to the lowest frequency value (Hz)")
    frequency_max: float = _setting(600.0, "centroid mapped to the highest frequency value (Hz)")
    output_min: float = _setting(0.0, "lowest frequency value (0..1)")
    output_max: float = _setting(1.0, "highest frequency value (0..1)")
    # breakpoint reduction: at most this many per second, then drop what is below the score
    amplitude_points_per_second: int = _setting(60, "most amplitude breakpoints kept per second")
    frequency_points_per_second: int = _setting(60, "most frequency breakpoints kept per second")
    minimum_score: float = _setting(1e-8, "least change (value x s) a breakpoint must carry")
    resolution: float = _setting(
        50.0,
        "how closely breakpoints follow the analysis: 100 all the budget allows, less "
        "drops points within a larger error (%)",
    )
    tolerance: float | None = _setting(
        None, "keep breakpoints within this error of the analysis instead of a count per second"
    )
    # emphasis: onsets that stand out of the sound around them (or Meta's amplitude peaks)
    emphasis: bool = _setting(True, "mark the sound's hits as emphasis")
    adaptive: bool = _setting(
        True, "find hits by how far they stand out of the sound around them (off: Meta's peaks)"
    )
    sensitivity: float = _setting(50.0, "how readily a hit gets emphasis: 0 none, 100 most (%)")
    peak_window: float = _setting(0.03, "least time between two emphasis points (s)")
    minimum_rise: float = _setting(0.1, "least amplitude rise into a peak (Meta's peaks only)")
    plateau: float = _setting(
        25.0, "how far the amplitude may keep rising after a peak (Meta's peaks only, %)"
    )
    sharpness_min: float = _setting(0.0, "emphasis frequency of the softest hit (0..1)")
    sharpness_max: float = _setting(1.0, "emphasis frequency of the sharpest hit (0..1)")
    ducking: float = _setting(20.0, "amplitude taken from the envelope under an emphasis (%)")

    def __post_init__(self) -> None:
        for f in fields(self):
            value = getattr(self, f.name)
            if isinstance(value, bool) or value is None:
                continue
            if not math.isfinite(value):
                raise SettingsError(f"the analysis setting {f.name} must be a finite number")
        for name in ("rms_window", "attack", "hold", "release", "peak_window", "minimum_rise"):
            if getattr(self, name) < 0:
                raise SettingsError(f"the analysis setting {name} must not be negative")
        if self.tail_db < 0 or self.tail_ratio < 1:
            raise SettingsError("tail_db must not be negative and tail_ratio must be at least 1")
        if self.update <= 0:
            raise SettingsError("the analysis setting update must be above zero")
        if self.fft_size < 16 or self.fft_size & (self.fft_size - 1):
            raise SettingsError("the analysis setting fft_size must be a power of two from 16")
        if not 1 <= self.overlap <= self.fft_size:
            raise SettingsError("the analysis setting overlap must be from 1 to fft_size")
        if not 0 <= self.frequency_min < self.frequency_max:
            raise SettingsError("frequency_min must be below frequency_max (both in Hz, from 0)")
        if self.centroid_lowpass <= 0:
            raise SettingsError("the analysis setting centroid_lowpass must be above zero")
        for name in ("amplitude_points_per_second", "frequency_points_per_second"):
            if getattr(self, name) < 2:
                raise SettingsError(f"the analysis setting {name} must be at least 2")
        if self.tolerance is not None and not 0 < self.tolerance <= 1:
            raise SettingsError("the analysis setting tolerance must be above 0 and at most 1")
        for name in ("sensitivity", "plateau", "ducking", "resolution"):
            if not 0 <= getattr(self, name) <= 100:
                raise SettingsError(f"the analysis setting {name} is a percentage (0 to 100)")
        for name in ("output_min", "output_max", "sharpness_min", "sharpness_max"):
            if not 0 <= getattr(self, name) <= 1:
                raise SettingsError(f"the analysis setting {name} must be from 0 to 1")

    @staticmethod
    def help(name: str) -> str:
        """What a setting does, in the user's words (for options and the editor's panel)."""
        return next(f.metadata["help"] for f in fields(AnalysisSettings) if f.name == name)

    @property
    def slack(self) -> float:
        """The error (0..1 of full scale) `resolution` lets breakpoint reduction add."""
        return SLACK_AT_ZERO * (1.0 - self.resolution / 100.0) ** 2

    @property
    def hop(self) -> int:
        """Samples between spectrum frames."""
        return max(1, self.fft_size // self.overlap)


DEFAULTS = AnalysisSettings()
