"""The settings of the sound-to-haptic analysis, with Meta Haptics Studio's defaults.

Every field is a setting of `haptic-timeline convert` and of the editor's analysis panel. The
defaults are those of Meta Haptics Studio's open analysis (facebook/meta-haptics-sdk,
interfaces/studio/audio_analysis), so a design made here starts where Studio's would.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields


class SettingsError(ValueError):
    """A setting outside the range the analysis can use."""


@dataclass(frozen=True)
class AnalysisSettings:
    """How a sound becomes amplitude and frequency envelopes and emphasis."""

    # amplitude: a windowed RMS, then an attack/hold/release follower, sampled every update
    rms_window: float = 1e-4  # s: length of the moving RMS window
    attack: float = 1e-4  # s: the follower reaches 99 % of a rise in this time
    hold: float = 1.5e-3  # s: the follower holds a peak this long before releasing
    release: float = 0.1  # s: the follower falls 99 % of the way in this time
    update: float = 1e-3  # s between analysed amplitude points
    normalize: bool = True  # scale the sound so its peak (less DC) is `level_db`
    level_db: float = 0.0  # dBFS peak level after normalisation
    gain_db: float = 0.0  # gain applied instead when normalize is off
    # frequency: the spectral centroid below `centroid_lowpass` mapped from a Hz range to 0..1
    fft_size: int = 1024  # samples per spectrum frame (a power of two)
    overlap: int = 8  # frames per frame length (hop = fft_size / overlap)
    centroid_lowpass: float = 1000.0  # Hz: bins above this are ignored by the centroid
    frequency_min: float = 30.0  # Hz mapped to frequency 0
    frequency_max: float = 600.0  # Hz mapped to frequency 1
    output_min: float = 0.0  # frequency value for frequency_min
    output_max: float = 1.0  # frequency value for frequency_max
    # breakpoint reduction: at most this many per second, then drop what is below the score
    amplitude_points_per_second: int = 60
    frequency_points_per_second: int = 60
    minimum_score: float = 1e-8  # twice the triangle area (value x s) a breakpoint must add
    # emphasis: amplitude peaks scored by spectral flux
    emphasis: bool = True
    sensitivity: float = 50.0  # %: 0 none, 100 every peak found
    peak_window: float = 0.1  # s: the least time between two emphasis points
    minimum_rise: float = 0.1  # amplitude rise into a peak
    plateau: float = 25.0  # %: how far the amplitude may keep rising after a peak
    sharpness_min: float = 0.0  # emphasis frequency of the least flux
    sharpness_max: float = 1.0  # emphasis frequency of the most flux
    ducking: float = 50.0  # %: amplitude taken from the envelope under an emphasis

    def __post_init__(self) -> None:
        for f in fields(self):
            value = getattr(self, f.name)
            if isinstance(value, bool):
                continue
            if not math.isfinite(value):
                raise SettingsError(f"the analysis setting {f.name} must be a finite number")
        for name in ("rms_window", "attack", "hold", "release", "peak_window", "minimum_rise"):
            if getattr(self, name) < 0:
                raise SettingsError(f"the analysis setting {name} must not be negative")
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
        for name in ("sensitivity", "plateau", "ducking"):
            if not 0 <= getattr(self, name) <= 100:
                raise SettingsError(f"the analysis setting {name} is a percentage (0 to 100)")
        for name in ("output_min", "output_max", "sharpness_min", "sharpness_max"):
            if not 0 <= getattr(self, name) <= 1:
                raise SettingsError(f"the analysis setting {name} must be from 0 to 1")

    @property
    def hop(self) -> int:
        """Samples between spectrum frames."""
        return max(1, self.fft_size // self.overlap)


DEFAULTS = AnalysisSettings()
