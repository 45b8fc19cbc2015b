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

F_MIN = 80.0  # Hz at sharpness 0
F_MAX = 230.0  # Hz at sharpness 1
TRANSIENT_CYCLES = 2  # a transient is two carrier cycles, fading out over the second
TRANSIENT_MAX = 0.05  # s: sine-generator clips up to this long export as transients
MAX_DURATION = 600.0  # s: longer designs are refused as hostile or broken
MAX_JSON_BYTES = 64 * 2**20
AMPLITUDE_TOLERANCE = 0.01  # envelope breakpoints reproduce the analysed envelope to this
SHARPNESS_TOLERANCE = 0.02
GRID = 0.001  # s between analysed envelope samples before simplification
ANALYSIS_WINDOW = 0.01  # s: carrier frequency window (about one period at F_MIN)
DRIVE = "drive"


def frequency(sharpness: np.ndarray | float) -> np.ndarray | float:
    """The carrier frequency (Hz) for a sharpness or normalised frequency in 0..1."""
    return F_MIN + np.clip(sharpness, 0.0, 1.0) * (F_MAX - F_MIN)


def sharpness(hz: np.ndarray | float) -> np.ndarray | float:
    """The sharpness (0..1) for a carrier frequency, clipped to the mapped range."""
    return np.clip((np.asarray(hz, dtype=np.float64) - F_MIN) / (F_MAX - F_MIN), 0.0, 1.0)


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


def _window_sum(values: np.ndarray, width: int) -> np.ndarray:
    return np.convolve(values, np.ones(width), "same")


def envelope_breakpoints(
    x: np.ndarray, rate: float
) -> tuple[list[tuple[float, float]], list[tuple[float, float]]]:
    """Amplitude and sharpness breakpoints of a waveform (fraction of full scale)."""
    padded = np.concatenate([[0.0], x, [0.0]])
    neighbours = padded[2:] + padded[:-2]
    width = max(3, int(round(ANALYSIS_WINDOW * rate)))
    energy = _window_sum(2.0 * x * x, width)
    cos_w = np.clip(_window_sum(x * neighbours, width) / np.maximum(energy, 1e-300), -1.0, 1.0)
    omega = np.arccos(cos_w)  # radians per sample of the local carrier
    # Where the signal is too weak to carry a frequency, take it from the nearest strong parts.
    reliable = energy / width > (AMPLITUDE_TOLERANCE / 2) ** 2
    index = np.arange(len(x))
    if reliable.any():
        omega = np.interp(index, index[reliable], omega[reliable])
    else:
        omega = np.full(len(x), 2.0 * np.pi * frequency(0.5) / rate)
    omega = np.clip(omega, np.pi * F_MIN / rate, min(4.0 * np.pi * F_MAX / rate, 0.9 * np.pi))
    quadrature = (padded[2:] - padded[:-2]) / (2.0 * np.maximum(np.sin(omega), 1e-6))
    envelope = np.sqrt(x * x + quadrature * quadrature)
    step = max(1, int(round(GRID * rate)))
    centres = np.arange(0, len(x), step)
    if centres[-1] != len(x) - 1:
        centres = np.append(centres, len(x) - 1)
    half = step // 2
    amp = np.array([np.median(envelope[max(0, c - half) : c + half + 1]) for c in centres])
    hz = omega[centres] * rate / (2.0 * np.pi)
    times = centres / rate
    return (
        simplify(times, np.clip(amp, 0.0, 1.0), AMPLITUDE_TOLERANCE),
        simplify(times, sharpness(hz), SHARPNESS_TOLERANCE),
    )


def simplify(t: np.ndarray, v: np.ndarray, tolerance: float) -> list[tuple[float, float]]:
    """Fewest breakpoints whose straight segments stay within tolerance of v (Douglas-Peucker)."""
    keep = np.zeros(len(t), dtype=bool)
    keep[[0, -1]] = True
    stack = [(0, len(t) - 1)]
    while stack:
        i, j = stack.pop()
        if j - i < 2:
            continue
        inner = np.arange(i + 1, j)
        line = v[i] + (v[j] - v[i]) * (t[inner] - t[i]) / (t[j] - t[i])
        errors = np.abs(v[inner] - line)
        worst = int(np.argmax(errors))
        if errors[worst] > tolerance:
            k = int(inner[worst])
            keep[k] = True
            stack += [(i, k), (k, j)]
    return [(float(t[k]), round(float(v[k]), 6)) for k in np.flatnonzero(keep)]


def trim_silence(points: list[tuple[float, float]]) -> list[tuple[float, float]]:
    """Drop leading and trailing breakpoints of a silent stretch, keeping the edge of the sound."""
    lo, hi = 0, len(points)
    while lo + 1 < hi and points[lo][1] == 0.0 and points[lo + 1][1] == 0.0:
        lo += 1
    while hi - 1 > lo + 1 and points[hi - 1][1] == 0.0 and points[hi - 2][1] == 0.0:
        hi -= 1
    return points[lo:hi]


def clip_points(
    points: list[tuple[float, float]], lo: float, hi: float
) -> list[tuple[float, float]]:
    """The breakpoints within [lo, hi], with values interpolated at lo and hi."""
    t = np.array([p[0] for p in points])
    v = np.array([p[1] for p in points])
    inner = [p for p in points if lo < p[0] < hi]
    ends = [(lo, float(np.interp(lo, t, v))), (hi, float(np.interp(hi, t, v)))]
    return [ends[0], *inner, ends[1]] if hi > lo else ends[:1]


def write_json(doc: Any, path: Path) -> None:
    """Write a JSON document (no NaN or infinity) with two-space indentation."""
    Path(path).write_text(json.dumps(doc, indent=2, allow_nan=False) + "\n", encoding="utf-8")
