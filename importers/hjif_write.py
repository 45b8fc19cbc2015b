"""Writing a project as an MPEG-I haptics interchange file (ISO/IEC 23090-31 .hjif).

The sounding drive tracks split in two. Those holding vibration designs, emphasis clips or sine
clips of at most TRANSIENT_MAX (read as emphasis, as .haptic export does) are read as one design
(timeline.edits.vibration.design_of, what .haptic export takes) and written as a Vibrotactile
perception: one channel with a VectorialWave band (one effect whose keyframes are the amplitude
breakpoints, amplitude_modulation 0..1, and the frequency breakpoints, frequency_modulation in
integer Hz on our carrier's F_MIN..F_MAX) and a Transient band (one keyframe per emphasis). The
other drive tracks are force layers: rendered, reduced to breakpoints within FORCE_TOLERANCE of
full scale and written as a Force perception's Curve band (linear, amplitude_modulation = drive /
full scale, clipped to -1..1).

Times are ticks of TIMESCALE per second (48,000, the Main profile's largest). The reference
decoder holds a vectorial effect's first and last amplitude over the whole effect, so where the
frequency envelope reaches outside the amplitude envelope the effect gets zero-amplitude
keyframes there; a design without a frequency envelope is written at DEFAULT_FREQUENCY, since the
decoder plays a keyframe without frequency at 0 Hz.
"""

from __future__ import annotations

import datetime as _dt
import os
from typing import Any

import numpy as np

from importers.hjif_read import LINEAR_NOTE
from timeline.analysis.breakpoints import simplify
from timeline.edits.vibration import (
    DRIVE,
    TRANSIENT_MAX,
    VibrationDesign,
    design_of,
    sharpness_convention,
)
from timeline.errors import EditError
from timeline.model import DEFAULT_TIME_RATE, Project, Track
from timeline.plugins.track_kinds import track_kind
from timeline.rendering import mixer
from timeline.signal.vibration_design import DEFAULT_FREQUENCY, F_MAX, F_MIN, carrier_hz
from timeline.tiles import GeneratorTile, VibrationTile

VERSION = "2023"  # ISO/IEC 23090-31 edition year, as the reference software writes it
TIMESCALE = 48_000
FORCE_TOLERANCE = 0.001  # of full scale: force breakpoints vs the rendered drive layer
CREATED = "haptic-timeline"

Points = list[tuple[float, float]]


def tick(t: float) -> int:
    """Seconds as ticks of TIMESCALE."""
    return int(round(t * TIMESCALE))


def hertz(f: float) -> int:
    """A normalised frequency (0..1) as the carrier's whole Hz."""
    return int(round(float(carrier_hz(f))))


def document(project: Project, rate: float | None = None, title: str = "") -> dict[str, Any]:
    """The .hjif document for a project's sounding drive tracks (`title`: its description)."""
    vibration, force = _split(project)
    if not vibration and not force:
        raise EditError("the project has no sounding drive track with clips")
    perceptions = []
    if vibration:
        design = design_of(project, [t.id for t in vibration], rate=rate)
        linear = sharpness_convention(project, [t.id for t in vibration]) == "linear"
        perceptions.append(_vibrotactile(design, len(perceptions), linear))
    if force:
        perceptions.append(_force(project, force, len(perceptions), rate))
    return {
        "version": VERSION,
        "profile": "Main",
        "level": 1,
        "date": written_on(),
        "description": f"{title or 'design'} ({CREATED})",
        "timescale": TIMESCALE,
        "avatars": [],
        "perceptions": perceptions,
        "syncs": [],
    }


def _split(project: Project) -> tuple[list[Track], list[Track]]:
    """The sounding drive tracks with clips: those holding vibration data (designs, emphasis
    clips, sine clips short enough to be read as emphasis), and force layers (the rest)."""
    vibration, force = [], []
    for track in mixer.active_tracks(project):
        if track.kind != DRIVE or not track.clips:
            continue
        designed = any(_vibration_clip(project.tile(c.tile_id), c.duration) for c in track.clips)
        (vibration if designed else force).append(track)
    return vibration, force


def _vibration_clip(tile: object, duration: float) -> bool:
    if isinstance(tile, VibrationTile):
        return True
    if not isinstance(tile, GeneratorTile):
        return False
    return tile.generator == "emphasis" or (tile.generator == "sine" and duration <= TRANSIENT_MAX)


def _perception(pid: int, description: str, modality: str, bands: list) -> dict[str, Any]:
    channel = {
        "id": 0,
        "description": "drive",
        "gain": 1.0,
        "mixing_coefficient": 1.0,
        "body_part_mask": 0,
        "bands": bands,
    }
    return {
        "id": pid,
        "avatar_id": 0,
        "description": description,
        "perception_modality": modality,
        "reference_devices": [],
        "effect_library": [],
        "channels": [channel],
    }


def _band(kind: str, lo: int, hi: int, effect: dict[str, Any]) -> dict[str, Any]:
    band: dict[str, Any] = {"band_type": kind}
    if kind == "Curve":
        band["curve_type"] = "Linear"
    band.update(lower_frequency_limit=lo, upper_frequency_limit=hi, effects=[effect])
    return band


def _effect(position: int, keyframes: list[dict[str, Any]]) -> dict[str, Any]:
    return {
        "effect_type": "Basis",
        "position": position,
        "phase": 0.0,
        "base_signal": "Sine",
        "keyframes": keyframes,
    }


def _vibrotactile(design: VibrationDesign, pid: int, linear: bool) -> dict[str, Any]:
    bands = []
    amplitude = list(design.amplitude)
    if len(amplitude) >= 2 and amplitude[-1][0] > amplitude[0][0]:
        frequency = list(design.frequency) or [(amplitude[0][0], DEFAULT_FREQUENCY)]
        bands.append(_vectorial(amplitude, frequency))
    if design.emphasis:
        first = tick(design.emphasis[0].time)
        keyframes = [
            {
                "relative_position": tick(e.time) - first,
                "amplitude_modulation": e.amplitude,
                "frequency_modulation": hertz(e.frequency),
            }
            for e in design.emphasis
        ]
        bands.append(_band("Transient", int(F_MIN), int(F_MAX), _effect(first, keyframes)))
    if not bands:  # a design of no length: a silent effect over its duration
        bands.append(_vectorial([(0.0, 0.0), (design.duration, 0.0)], [(0.0, DEFAULT_FREQUENCY)]))
    description = f"vibration ({CREATED}; {LINEAR_NOTE})" if linear else f"vibration ({CREATED})"
    return _perception(pid, description, "Vibrotactile", bands)


def _vectorial(amplitude: Points, frequency: Points) -> dict[str, Any]:
    """One vectorial effect: amplitude and frequency keyframes merged in time order."""
    start = min(amplitude[0][0], frequency[0][0])
    end = max(amplitude[-1][0], frequency[-1][0])
    if start < amplitude[0][0]:  # silent until the amplitude envelope starts
        lead = [(start, 0.0)] + ([(amplitude[0][0], 0.0)] if amplitude[0][1] else [])
        amplitude = lead + amplitude
    if end > amplitude[-1][0]:
        tail = ([(amplitude[-1][0], 0.0)] if amplitude[-1][1] else []) + [(end, 0.0)]
        amplitude = amplitude + tail
    position = tick(start)
    events = [(tick(t), 0, k, v) for k, (t, v) in enumerate(amplitude)]
    events += [(tick(t), 1, k, hertz(v)) for k, (t, v) in enumerate(frequency)]
    keyframes: list[dict[str, Any]] = []
    for at, kind, _, value in sorted(events, key=lambda e: (e[0], e[2], e[1])):
        field = "amplitude_modulation" if kind == 0 else "frequency_modulation"
        last = keyframes[-1] if keyframes else None
        if last is None or last["relative_position"] != at - position or field in last:
            last = {"relative_position": at - position}
            keyframes.append(last)
        last[field] = value
    return _band("VectorialWave", int(F_MIN), int(F_MAX), _effect(position, keyframes))


def _force(project: Project, tracks: list[Track], pid: int, rate: float | None) -> dict[str, Any]:
    """The force layers rendered and reduced to a linear curve band."""
    rate = float(rate or project.rate or DEFAULT_TIME_RATE)
    end = max(c.end for t in tracks for c in t.clips)
    ids = [t.id for t in tracks]
    layer = mixer.render(project, 0.0, end, rate, "normal", ids).get(DRIVE)
    if layer is None or len(layer) == 0:
        layer = np.zeros(2)
    values = np.clip(layer / track_kind(DRIVE).full_scale, -1.0, 1.0)
    times = np.arange(len(values)) / rate
    points = simplify(times, values, FORCE_TOLERANCE)
    keyframes = [{"relative_position": tick(t), "amplitude_modulation": v} for t, v in points]
    hi = int(min(rate / 2, TIMESCALE / 2))
    band = _band("Curve", 0, hi, _effect(0, keyframes))
    full = track_kind(DRIVE).full_scale
    return _perception(pid, f"drive torque, 1 = {full:g} N*m ({CREATED})", "Force", [band])


def written_on() -> str:
    """The file's date (UTC, ISO): SOURCE_DATE_EPOCH's when set (reproducible builds' convention,
    reproducible-builds.org/specs/source-date-epoch), else today's."""
    epoch = os.environ.get("SOURCE_DATE_EPOCH", "").strip()
    moment = _dt.datetime.fromtimestamp(int(epoch), _dt.UTC) if epoch.isdigit() else None
    return (moment or _dt.datetime.now(_dt.UTC)).date().isoformat()
