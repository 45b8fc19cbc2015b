"""Reading MPEG-I haptics interchange files (ISO/IEC 23090-31 .hjif) into channel contents.

A file holds perceptions (a modality: Vibrotactile, Force, ...), each with channels, each with
bands of effects whose keyframes carry a relative position (ticks of the file's `timescale` per
second; 1000 when a file has none), an amplitude_modulation (-1..1) and a frequency_modulation
(integer Hz). What a band means follows the reference decoder (MPEGGroup/HapticReferenceSoftware,
Effect::EvaluateVectorial / EvaluateTransient / EvaluateKeyframes):

* VectorialWave: a carrier whose amplitude and frequency are linear between keyframes, holding
  the nearest keyframe's value before the first and after the last, for the effect's length (its
  last keyframe). Read as a vibration design's amplitude (|amplitude_modulation|) and frequency
  envelopes; several effects join (overlapping ones add, clipped at 1).
* Transient: each keyframe a short pulse at its amplitude and frequency: read as emphasis.
* Curve: a low-frequency signal (linear or cubic between keyframes): read as a force layer,
  sampled at CURVE_RATE, 1.0 = the drive track's full scale.

Reference effects are looked up in the perception's effect library. Wavelet bands (sampled
signals), composite effects and perceptions other than vibration and force are skipped with a
note. Real files written through the binary codec can carry a stray keyframe far past its
neighbours (relative_position 65534 before 0); a keyframe later than one after it is dropped.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from importers import _vibration as vib
from timeline.plugins.file_formats import FormatError
from timeline.signal.vibration_design import (
    DEFAULT_FREQUENCY,
    F_MAX,
    F_MIN,
    Emphasis,
    normalised_frequency,
)

WHAT = ".hjif"
DEFAULT_TIMESCALE = 1000  # ticks per second of files written before `timescale` existed
MAX_TIMESCALE = 10**7
MAX_KEYFRAMES = 500_000  # keyframes read from one file (a bound on time and memory)
CURVE_RATE = 10_000.0  # Hz: curve bands are sampled at the knob's servo rate
MAX_CURVE_SAMPLES = int(vib.MAX_DURATION * CURVE_RATE)  # samples of all curves of one file
VIBRATION = {"Vibrotactile", "Vibration", "Other"}
FORCE = {"Force", "Kinesthetic"}
LINEAR_NOTE = "sharpness = frequency"  # in a perception's description: AHAP convention linear

Points = list[tuple[float, float]]


@dataclass
class ChannelContent:
    """What one channel holds: a vibration design's pieces and force curves."""

    name: str
    amplitude: Points = field(default_factory=list)
    frequency: Points = field(default_factory=list)
    emphasis: list[Emphasis] = field(default_factory=list)
    curves: list[tuple[float, np.ndarray]] = field(default_factory=list)  # (start s, samples)
    linear: bool = False  # AHAP sharpness convention "linear" (written by haptic-timeline)

    @property
    def has_design(self) -> bool:
        return len(self.amplitude) >= 2 or bool(self.emphasis)

    @property
    def duration(self) -> float:
        ends = [t for t, _ in self.amplitude + self.frequency]
        ends += [e.time + e.length for e in self.emphasis]
        return max(ends, default=0.0)


@dataclass
class _Effect:
    """One effect's keyframes in seconds from the file's start."""

    start: float
    times: list[float]  # absolute seconds, non-decreasing
    amplitude: list[float | None]
    frequency: list[float | None]  # Hz

    @property
    def end(self) -> float:
        return self.times[-1] if self.times else self.start


class _Reader:
    def __init__(self, name: str) -> None:
        self.name = name
        self.notes: list[str] = []
        self.keyframes = 0
        self.dropped = 0
        self.clipped_hz = 0
        self.curve_samples = 0

    def fail(self, where: str, what: str) -> FormatError:
        return FormatError(f"{self.name}: {where} {what}")

    def obj(self, value: Any, where: str) -> dict[str, Any]:
        if not isinstance(value, dict):
            raise self.fail(where, "is not an object")
        return value

    def items(self, parent: dict[str, Any], key: str, where: str, required: bool = True) -> list:
        value = parent.get(key)
        if value is None and not required:
            return []
        if not isinstance(value, list):
            raise self.fail(where, f"has no {key} list")
        return value

    def text(self, parent: dict[str, Any], key: str, where: str, default: str = "") -> str:
        value = parent.get(key, default)
        if not isinstance(value, str):
            raise self.fail(where, f"has a {key} that is not text")
        return value

    def integer(self, value: Any, where: str, lo: float, hi: float) -> int:
        number = vib.number(value, f"{self.name}: {where}", lo, hi)
        if number != math.floor(number):
            raise self.fail(where, f"must be a whole number, not {number:g}")
        return int(number)


def read_channels(path: Path) -> tuple[list[ChannelContent], list[str]]:
    """The channels of every vibration and force perception in the file, and notes."""
    path = Path(path)
    doc = vib.load_json(path, WHAT)
    r = _Reader(path.name)
    if not isinstance(doc, dict) or not isinstance(doc.get("perceptions"), list):
        raise FormatError(f"{path.name} is not an .hjif file (it has no perceptions list)")
    timescale = DEFAULT_TIMESCALE
    if doc.get("timescale") is not None:
        timescale = r.integer(doc["timescale"], "the timescale", 1, MAX_TIMESCALE)
    channels: list[ChannelContent] = []
    for k, perception in enumerate(doc["perceptions"]):
        channels += _perception(r, perception, f"perception {k + 1}", timescale)
    if r.dropped:
        r.notes.append(f"{r.dropped} keyframe(s) later than the keyframes after them were dropped")
    if r.clipped_hz:
        r.notes.append(
            f"{r.clipped_hz} frequency value(s) outside {F_MIN:g}-{F_MAX:g} Hz were clipped to it"
        )
    if not any(c.has_design or c.curves for c in channels):
        raise FormatError(f"{path.name} holds no vibration or force effect that lasts any time")
    return channels, r.notes


def _perception(r: _Reader, value: Any, where: str, timescale: int) -> list[ChannelContent]:
    perception = r.obj(value, where)
    modality = r.text(perception, "perception_modality", where)
    if modality not in VIBRATION | FORCE:
        r.notes.append(f"{where} ({modality or 'no modality'}) is not vibration or force: skipped")
        return []
    description = r.text(perception, "description", where)
    library: dict[int, dict[str, Any]] = {}
    for k, effect in enumerate(r.items(perception, "effect_library", where, required=False)):
        here = f"{where}, library effect {k + 1}"
        effect = r.obj(effect, here)
        library[r.integer(effect.get("id"), f"{here} id", -(2**31), 2**31)] = effect
    out = []
    for k, channel in enumerate(r.items(perception, "channels", where)):
        here = f"{where}, channel {k + 1}"
        content = _channel(r, r.obj(channel, here), here, timescale, library)
        content.linear = LINEAR_NOTE in description
        out.append(content)
    return out


def _channel(r: _Reader, channel: dict, where: str, timescale: int, library) -> ChannelContent:
    content = ChannelContent(r.text(channel, "description", where) or where)
    waves: list[_Effect] = []
    for k, band in enumerate(r.items(channel, "bands", where)):
        here = f"{where}, band {k + 1}"
        band = r.obj(band, here)
        kind = r.text(band, "band_type", here)
        if kind not in ("VectorialWave", "Transient", "Curve"):
            r.notes.append(f"{here}: {kind or 'untyped'} bands are not read (skipped)")
            continue
        effects = _effects(r, band, here, timescale, library)
        if kind == "VectorialWave":
            waves += effects
        elif kind == "Transient":
            content.emphasis += _transients(r, effects)
        else:
            curve = r.text(band, "curve_type", here, "Linear")
            for e in effects:
                r.curve_samples += int(round((e.end - e.start) * CURVE_RATE)) + 1
                if r.curve_samples > MAX_CURVE_SAMPLES:
                    raise FormatError(
                        f"{r.name}: its curves last more than {vib.MAX_DURATION:g} s in all"
                    )
                content.curves.append(_curve(e, curve))
    if waves:
        content.amplitude, content.frequency = _envelopes(r, waves)
    return content


def _effects(r: _Reader, band: dict, where: str, timescale: int, library) -> list[_Effect]:
    out = []
    for k, effect in enumerate(r.items(band, "effects", where)):
        here = f"{where}, effect {k + 1}"
        effect = r.obj(effect, here)
        kind = effect.get("effect_type", "Basis")
        position = r.integer(effect.get("position", 0), f"{here} position", 0, math.inf)
        if kind == "Reference":
            ref = r.integer(effect.get("id"), f"{here} id", -(2**31), 2**31)
            if ref not in library:
                r.notes.append(f"{here} refers to library effect {ref}, which is missing: skipped")
                continue
            effect = library[ref]
        elif kind != "Basis":
            r.notes.append(f"{here}: {kind} effects are not read (skipped)")
            continue
        if position / timescale > vib.MAX_DURATION:
            raise r.fail(here, f"starts after {vib.MAX_DURATION:g} s")
        out.append(_keyframes(r, r.items(effect, "keyframes", here), here, position, timescale))
    return out


def _keyframes(r: _Reader, items: list, where: str, position: int, timescale: int) -> _Effect:
    """An effect's keyframes; times are whole ticks divided once, so equal ticks in two effects
    give equal seconds."""
    r.keyframes += len(items)
    if r.keyframes > MAX_KEYFRAMES:
        raise FormatError(f"{r.name} has more than {MAX_KEYFRAMES:,} keyframes, the most read")
    ticks, amps, freqs = [], [], []
    previous = 0
    for k, kf in enumerate(items):
        here = f"{where}, keyframe {k + 1}"
        kf = r.obj(kf, here)
        tick = previous
        if kf.get("relative_position") is not None:
            limit = vib.MAX_DURATION * timescale
            tick = r.integer(kf["relative_position"], f"{here} relative_position", 0, limit)
        previous = tick
        amp = kf.get("amplitude_modulation")
        freq = kf.get("frequency_modulation")
        ticks.append(tick)
        amps.append(None if amp is None else vib.number(amp, f"{r.name}: {here} amplitude"))
        freqs.append(None if freq is None else vib.number(freq, f"{r.name}: {here} frequency", 0))
    keep = _in_order(ticks)
    r.dropped += len(ticks) - int(keep.sum())
    times = [(position + t) / timescale for t, ok in zip(ticks, keep, strict=True) if ok]
    if times and times[-1] > vib.MAX_DURATION:
        raise r.fail(where, f"lasts past {vib.MAX_DURATION:g} s")
    amps = [a for a, ok in zip(amps, keep, strict=True) if ok]
    freqs = [f for f, ok in zip(freqs, keep, strict=True) if ok]
    return _Effect(position / timescale, times, amps, freqs)


def _in_order(ticks: list[int]) -> np.ndarray:
    """Which keyframes to keep: those not later than any keyframe after them."""
    t = np.array(ticks, dtype=np.float64)
    if len(t) == 0:
        return np.zeros(0, dtype=bool)
    later_min = np.minimum.accumulate(t[::-1])[::-1]
    return t <= later_min


def _level(a: float) -> float:
    """A keyframe's amplitude as a vibration level: its magnitude, at most 1."""
    return min(abs(a), 1.0)


def _unit_frequency(r: _Reader, hz: float) -> float:
    if not F_MIN <= hz <= F_MAX:
        r.clipped_hz += 1
    return float(normalised_frequency(hz))


def _transients(r: _Reader, effects: list[_Effect]) -> list[Emphasis]:
    out = []
    for e in effects:
        for t, a, f in zip(e.times, e.amplitude, e.frequency, strict=True):
            if a is None:
                continue
            freq = DEFAULT_FREQUENCY if f is None else _unit_frequency(r, f)
            out.append(Emphasis(t, _level(a), freq))
    return out


def _curve(e: _Effect, curve_type: str) -> tuple[float, np.ndarray]:
    """A curve effect sampled at CURVE_RATE from its first keyframe (cubic: the reference
    decoder's Hermite with flat ends; every other type linear)."""
    pts = [(t, a) for t, a in zip(e.times, e.amplitude, strict=True) if a is not None]
    if not pts:
        return e.start, np.zeros(1)
    t = np.array([p[0] for p in pts])
    v = np.clip(np.array([p[1] for p in pts]), -1.0, 1.0)
    n = int(round((t[-1] - t[0]) * CURVE_RATE)) + 1
    u = t[0] + np.arange(n) / CURVE_RATE
    if curve_type != "Cubic" or len(t) < 2:
        return float(t[0]), np.interp(u, t, v)
    k = np.clip(np.searchsorted(t, u, side="right") - 1, 0, len(t) - 2)
    h = t[k + 1] - t[k]
    x = np.where(h > 0, (u - t[k]) / np.where(h > 0, h, 1.0), 1.0)
    return float(t[0]), v[k] + (v[k + 1] - v[k]) * x * x * (3 - 2 * x)


def _effect_envelopes(r: _Reader, e: _Effect) -> tuple[Points, Points]:
    """One vectorial effect's amplitude and frequency points over [its start, its end]."""
    amp = [(t, _level(a)) for t, a in zip(e.times, e.amplitude, strict=True) if a is not None]
    freq = [
        (t, _unit_frequency(r, f))
        for t, f in zip(e.times, e.frequency, strict=True)
        if f is not None
    ]
    if not amp:
        amp = [(e.start, 1.0)]  # no amplitude keyframe: the carrier at full amplitude
    if amp[0][0] > e.start:
        amp.insert(0, (e.start, amp[0][1]))
    if amp[-1][0] < e.end:
        amp.append((e.end, amp[-1][1]))
    return amp, freq


def _envelopes(r: _Reader, effects: list[_Effect]) -> tuple[Points, Points]:
    """The channel's vectorial effects as one amplitude and one frequency envelope."""
    effects = sorted((e for e in effects if e.times), key=lambda e: e.start)
    pieces = [_effect_envelopes(r, e) for e in effects]
    disjoint = all(b.start >= a.end for a, b in zip(effects, effects[1:], strict=False))
    if not disjoint:
        r.notes.append("overlapping vectorial effects were added together (clipped at 1)")
        return _summed([p[0] for p in pieces]), sorted(f for p in pieces for f in p[1])
    amplitude: Points = []
    for k, (amp, _) in enumerate(pieces):
        amp = list(amp)
        if k > 0 and amp[0][1] > 0:
            amp.insert(0, (amp[0][0], 0.0))  # silent between effects
        if k < len(pieces) - 1 and amp[-1][1] > 0:
            amp.append((amp[-1][0], 0.0))
        amplitude += amp
    return amplitude, [f for p in pieces for f in p[1]]


def _summed(pieces: list[Points]) -> Points:
    """Piecewise-linear envelopes (zero outside their spans) added at every knot, with both
    sides of each step, clipped at 1."""
    knots = np.unique([t for p in pieces for t, _ in p])

    def total(left: bool) -> np.ndarray:
        out = np.zeros(len(knots))
        for p in pieces:
            t = np.array([q[0] for q in p])
            v = np.array([q[1] for q in p])
            inside = (
                (knots > t[0]) & (knots <= t[-1]) if left else (knots >= t[0]) & (knots < t[-1])
            )
            out += np.where(inside, np.interp(knots, t, v), 0.0)
        return np.minimum(out, 1.0)

    lo, hi = total(left=True), total(left=False)
    hi[-1] = lo[-1]
    points: Points = []
    for t, a, b in zip(knots.tolist(), lo.tolist(), hi.tolist(), strict=True):
        if points and a != b:
            points.append((t, a))
        points.append((t, b))
    return points
