"""Quality presets: how the mixer trades speed for accuracy (measured: `haptic-timeline bench
quality`, numbers in docs/accuracy.md)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from timeline.errors import HapticTimelineError

if TYPE_CHECKING:
    import numpy as np


@dataclass(frozen=True)
class QualityPreset:
    """How sampled tiles are resampled, how often shapes are evaluated, and the output dtype."""

    name: str
    resampler: str  # "linear" (interpolate the source), or a soxr quality: "soxr-hq", "soxr-vhq"
    interpolation: str  # with the linear resampler: "linear" or "cubic" between source samples
    control_decimation: int  # evaluate generators/splines every Nth sample, linear in between
    dtype: Any  # anything numpy.dtype() takes: "float64", numpy.float32, ...

    @property
    def numpy_dtype(self) -> np.dtype:
        import numpy as np  # not at import: the command line's --help does without numpy

        return np.dtype(self.dtype)


PRESETS: dict[str, QualityPreset] = {
    # Measured (docs/accuracy.md): decimating shape evaluation saved no measurable time but cost
    # up to 46 % error on a 20-400 Hz chirp, so draft evaluates every sample; float32 output was
    # no faster (the mixer sums in float64), so every preset returns float64. Draft resamples
    # recordings by linear interpolation (no anti-aliasing), the others band-limited with soxr.
    "draft": QualityPreset("draft", "linear", "linear", 1, "float64"),
    "normal": QualityPreset("normal", "soxr-hq", "cubic", 1, "float64"),
    "exact": QualityPreset("exact", "soxr-vhq", "cubic", 1, "float64"),
}

DEFAULT_QUALITY = "normal"


def preset(name: str | QualityPreset) -> QualityPreset:
    """Look up a preset by name, or raise one clear sentence naming the choices."""
    if isinstance(name, QualityPreset):
        return name
    try:
        return PRESETS[name]
    except KeyError:
        raise HapticTimelineError(
            f"unknown quality {name!r} (choose from {', '.join(PRESETS)})"
        ) from None
