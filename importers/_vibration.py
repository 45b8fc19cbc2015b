"""Envelope-and-carrier haptics (AHAP, .haptic) to and from drive waveforms.

Both formats describe vibration as an amplitude envelope (0..1 of full scale) and a normalised
frequency or "sharpness" (0..1) over time, plus short transients. Reading synthesises the drive
waveform amplitude * sin(2*pi*integral of f) with f = F_MIN + sharpness * (F_MAX - F_MIN);
transients become short sine-generator clips. Writing analyses a drive layer back into
breakpoints (a local least-squares carrier estimate and a quadrature envelope, simplified to a
stated tolerance); sine-generator clips of at most TRANSIENT_MAX seconds become transients.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from timeline import edits, mixer
from timeline.formats import FormatError, Imported, Placement
from timeline.kinds import track_kind
from timeline.model import DEFAULT_TIME_RATE, Clip, Fade, Project, Track
from timeline.tiles import GeneratorTile, SampledTile, generator
from timeline.vibration_analysis import clip_points, envelope_breakpoints, trim_silence
from timeline.vibration_design import carrier_hz as frequency
from timeline.vibration_design import normalised_frequency as sharpness

TRANSIENT_CYCLES = 2  # a transient is two carrier cycles, fading out over the second
TRANSIENT_MAX = 0.05  # s: sine-generator clips up to this long export as transients
MAX_DURATION = 600.0  # s: longer designs are refused as hostile or broken
MAX_JSON_BYTES = 64 * 2**20
DRIVE = "drive"


def load_json(path: Path, what: str) -> Any:
    """Parse a JSON file, or a FormatError naming the format."""
    raw = path.read_bytes()
    if len(raw) > MAX_JSON_BYTES:
        raise FormatError(f"{path.name} is too large to be an {what} file")
    try:
        return json.loads(raw.decode("utf-8-sig"))
    except (UnicodeDecodeError, ValueError, RecursionError):
        raise FormatError(f"{path.name} is not an {what} file (it is not valid JSON)") from None


def number(value: Any, where: str, lo: float = -math.inf, hi: float = math.inf) -> float:
    """A finite JSON number within [lo, hi], or a FormatError saying where."""
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise FormatError(f"{where} must be a number")
    value = float(value)
    if not (math.isfinite(value) and lo <= value <= hi):
        raise FormatError(f"{where} must be between {lo:g} and {hi:g}, not {value:g}")
    return value


def grid_length(duration: float, rate: float) -> int:
    """Samples needed to synthesise `duration` seconds, refusing hostile lengths."""
    if duration > MAX_DURATION:
        raise FormatError(f"the design lasts {duration:g} s, longer than {MAX_DURATION:g} s")
    return max(1, int(math.ceil(duration * rate)) + 1)


def synthesise(amplitude: np.ndarray, sharp: np.ndarray, rate: float) -> np.ndarray:
    """The drive waveform for per-sample amplitude and sharpness."""
    phase = 2.0 * np.pi * np.cumsum(frequency(sharp)) / rate
    return amplitude * np.sin(phase)


def transient_placement(time: float, intensity: float, sharp: float, track: str = "") -> Placement:
    """A transient as a short sine clip: two cycles at the sharpness's frequency, fading out."""
    hz = float(frequency(sharp))
    length = TRANSIENT_CYCLES / hz
    tile = generator("sine", length, title=f"transient {sharp:.2f}", frequency=hz)
    clip = {"gain": intensity, "fade_out": Fade(length / TRANSIENT_CYCLES, "linear")}
    return Placement(tile, start=time, kind=DRIVE, track=track, clip=clip)


def continuous_placement(
    amplitude: np.ndarray, sharp: np.ndarray, rate: float, start: float, title: str, source: str
) -> Placement:
    """The synthesised continuous part as one sampled drive clip starting at `start`."""
    tile = SampledTile(synthesise(amplitude, sharp, rate), rate, title, source)
    return Placement(tile, start=start, kind=DRIVE)


def imported(placements: list[Placement], notes: list[str], name: str) -> Imported:
    """The placements, or a FormatError when the file holds nothing to play."""
    if not placements:
        raise FormatError(f"{name} holds no haptic events")
    return Imported(tuple(placements), notes=tuple(notes))


# --- analysis (writing) -------------------------------------------------------------------------


@dataclass(frozen=True)
class Transient:
    time: float
    intensity: float
    sharpness: float


@dataclass(frozen=True)
class Analysis:
    """A drive layer as envelope breakpoints (time, value) and transients."""

    amplitude: list[tuple[float, float]]
    sharpness: list[tuple[float, float]]
    transients: list[Transient]
    duration: float


def _track_factor(track: Track) -> float:
    """How a track scales its clips relative to the drive kind's full scale."""
    kind_scale = track_kind(track.kind).full_scale
    return track.gain * (track.full_scale or kind_scale) / kind_scale


def _as_transient(project: Project, track: Track, clip: Clip) -> Transient | None:
    tile = project.tile(clip.tile_id)
    if not (
        isinstance(tile, GeneratorTile)
        and tile.generator == "sine"
        and clip.duration <= TRANSIENT_MAX
        and clip.offset == 0.0
    ):
        return None
    level = abs(clip.gain * clip.scale * tile.param("amplitude") * _track_factor(track))
    hz = tile.param("frequency") / clip.stretch
    return Transient(clip.start, min(level, 1.0), float(sharpness(hz)))


def analyse(project: Project, rate: float | None = None) -> Analysis:
    """Split the sounding drive tracks into transients and an analysed continuous envelope."""
    rate = float(rate or project.rate or DEFAULT_TIME_RATE)
    drive = [t for t in mixer.active_tracks(project) if t.kind == DRIVE]
    if not drive:
        raise FormatError("the project has no sounding drive track to export")
    transients, transient_ids = [], []
    for track in drive:
        for clip in track.clips:
            found = _as_transient(project, track, clip)
            if found is not None:
                transients.append(found)
                transient_ids.append(clip.id)
    rest = edits.remove_clips(project, transient_ids)
    duration = max((c.end for t in drive for c in t.clips), default=0.0)
    layer = mixer.render(rest, 0.0, duration, rate, "normal", [t.id for t in drive]).get(DRIVE)
    if layer is None or not np.any(layer):
        amp = [(0.0, 0.0), (duration, 0.0)]
        sharp = [(0.0, 0.5)]
    else:
        amp, sharp = envelope_breakpoints(layer / track_kind(DRIVE).full_scale, rate)
        amp = trim_silence(amp)
        sharp = clip_points(sharp, amp[0][0], amp[-1][0])
    transients.sort(key=lambda t: t.time)
    return Analysis(amp, sharp, transients, duration)


def write_json(doc: Any, path: Path) -> None:
    """Write a JSON document (no NaN or infinity) with two-space indentation."""
    Path(path).write_text(json.dumps(doc, indent=2, allow_nan=False) + "\n", encoding="utf-8")
