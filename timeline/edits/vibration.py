"""Vibrotactile designs on the timeline: envelopes and emphasis kept as editable data.

The shared interface for .haptic/AHAP import and export and for `convert`:

* `VibrationDesign(amplitude, frequency, emphasis, duration)`: amplitude breakpoints
  (seconds, 0..1 of full scale), frequency breakpoints (seconds, 0..1 normalised frequency as in
  .haptic, carrier F_MIN..F_MAX Hz), `Emphasis(time, amplitude, frequency)` accents, length in
  seconds (timeline.signal.vibration_design).
* `place_design(project, design, *, at=0.0, track_id=None, ...) -> Project`: the envelopes as
  one `VibrationTile` in the library and one clip on a drive track (the first one, created if
  there is none, or `track_id`), and each emphasis as a clip of its own (an "emphasis" generator
  tile: amplitude and frequency parameters) on the drive track "Emphasis" just below it, so
  moving, deleting or copying an emphasis is an ordinary clip edit. The tile keeps the
  breakpoints; the carrier is synthesised only when rendering, exactly at any rate.
  `design_placements` does the same for an importer.
* `emphasis_of(project, clip_id)` / `with_emphasis(project, clip_ids)`: the emphasis clips that
  belong to a design clip (on the Emphasis track just below, starting within its span), which
  the editor moves, copies, duplicates and deletes with it.
* `design_of(project, track_ids=None) -> VibrationDesign`: the sounding drive tracks read back as
  a design, in timeline seconds. Exact (the same breakpoints) while the design's clips are
  unedited; clip gain, track gain, trims and squeeze-stretch are applied to the breakpoints
  exactly (a stretch that takes the carrier outside F_MIN..F_MAX is analysed instead, below);
  fades multiply the amplitude envelope, reduced back to breakpoints within EDIT_TOLERANCE.
  Emphasis clips are read as emphasis at their start (their gains and a squeeze-stretch applied),
  as are short sine-generator clips (at most TRANSIENT_MAX s). Anything else on
  the drive tracks (recordings, generators, overlapping, looped, reversed or offset clips) is
  rendered and analysed into breakpoints within the tolerances of timeline.analysis.breakpoints.
"""

from __future__ import annotations

from bisect import bisect_left, bisect_right
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, overload

import numpy as np

from timeline import edits
from timeline.errors import EditError
from timeline.model import DEFAULT_TIME_RATE, Clip, Project, Track
from timeline.plugins.track_kinds import track_kind
from timeline.rendering import mixer
from timeline.signal.fades import fade_envelope
from timeline.signal.vibration_design import (
    DEFAULT_FREQUENCY,
    F_MAX,
    F_MIN,
    Breakpoints,
    Emphasis,
    VibrationDesign,
    breakpoints,
    carrier_hz,
    emphasis_length,
    normalised_frequency,
)
from timeline.tiles import GeneratorTile
from timeline.tiles.vibration_tile import VibrationTile

if TYPE_CHECKING:  # a reader's types and the breakpoints load where used (not for a first paint)
    from timeline.plugins.file_formats import Imported

__all__ = [
    "DRIVE",
    "EDIT_TOLERANCE",
    "EMPHASIS_TRACK",
    "TRANSIENT_MAX",
    "Emphasis",
    "VibrationDesign",
    "VibrationTile",
    "design_of",
    "design_placements",
    "emphasis_of",
    "emphasis_tile",
    "place_design",
    "with_emphasis",
]

DRIVE = "drive"
EMPHASIS = "emphasis"  # the generator of emphasis clips
EMPHASIS_TRACK = "Emphasis"  # the drive track an emphasis goes on, below its design's track
TRANSIENT_MAX = 0.05  # s: sine-generator clips up to this long are read as emphasis
EDIT_TOLERANCE = 0.005  # max amplitude error of breakpoints reduced after a fade
FADE_GRID = 0.001  # s between fade samples before reduction


def place_design(project: Project, design: VibrationDesign, **options: Any) -> Project:
    """Put a design on the timeline as editable data (options: place_design_clip's)."""
    return place_design_clip(project, design, **options)[0]


def place_design_clip(
    project: Project,
    design: VibrationDesign,
    *,
    at: float = 0.0,
    track_id: str | None = None,
    name: str = "vibration",
    source: str = "",
    sharpness: str = "sqrt",
) -> tuple[Project, str]:
    """place_design, also returning the id of the envelopes' clip."""
    if track_id is None:
        track_id = next((t.id for t in project.tracks if t.kind == DRIVE), None)
        if track_id is None:
            project, track_id = edits.add_track(project, DRIVE)
    elif project.track(track_id).kind != DRIVE:
        raise EditError("a vibration design goes on a drive track")
    envelopes, accents = _split(design)
    tile = VibrationTile(envelopes, name, source, sharpness)
    project, tile_id = edits.add_tile(project, tile)
    project, clip_id = edits.add_clip(project, track_id, tile_id, at)
    if accents:
        project, accent_track = _emphasis_track(project, track_id)
        clips = [(accent_track, emphasis_tile(e), at + e.time, {}) for e in accents]
        project, _ = edits.add_clips(project, clips)
    return project, clip_id


def design_placements(
    design: VibrationDesign, name: str, source: str, sharpness: str, notes: tuple[str, ...] = ()
) -> Imported:
    """What a reader of a design file returns: place_design's clips as placements."""
    from timeline.plugins.file_formats import Imported, Placement, TrackInfo

    envelopes, accents = _split(design)
    placements = [Placement(VibrationTile(envelopes, name, source, sharpness), kind=DRIVE)]
    tiles: dict[tuple[float, float], GeneratorTile] = {}  # equal emphases share one tile
    for e in accents:
        tile = tiles.get((e.amplitude, e.frequency))
        if tile is None:
            tile = tiles[e.amplitude, e.frequency] = emphasis_tile(e)
        placements.append(Placement(tile, start=e.time, kind=DRIVE, track=EMPHASIS))
    tracks = (TrackInfo(EMPHASIS, EMPHASIS_TRACK, DRIVE),) if accents else ()
    return Imported(tuple(placements), tracks, notes)


def emphasis_tile(e: Emphasis) -> GeneratorTile:
    """An emphasis as a tile: its pulse, as long as the pulse, placed at the emphasis' time."""
    params = (("amplitude", e.amplitude), ("frequency", e.frequency))
    return GeneratorTile(EMPHASIS, emphasis_length(e.frequency), params, EMPHASIS)


def _split(design: VibrationDesign) -> tuple[VibrationDesign, tuple[Emphasis, ...]]:
    """The design's envelopes (same length, no emphasis) and its emphasis."""
    envelopes = VibrationDesign(design.amplitude, design.frequency, (), design.duration)
    return envelopes, design.emphasis


def _emphasis_below(project: Project, track_id: str) -> Track | None:
    """The drive track named EMPHASIS_TRACK just below `track_id`, if there is one."""
    index = next(k for k, t in enumerate(project.tracks) if t.id == track_id)
    below = project.tracks[index + 1] if index + 1 < len(project.tracks) else None
    if below is not None and below.kind == DRIVE and below.name == EMPHASIS_TRACK:
        return below
    return None


def _emphasis_track(project: Project, track_id: str) -> tuple[Project, str]:
    """The drive track named EMPHASIS_TRACK just below `track_id`, added there if missing."""
    below = _emphasis_below(project, track_id)
    if below is not None:
        return project, below.id
    index = next(k for k, t in enumerate(project.tracks) if t.id == track_id)
    project, new = edits.add_track(project, DRIVE, EMPHASIS_TRACK)
    return edits.move_track(project, new, index + 1), new


def emphasis_of(project: Project, clip_id: str) -> list[str]:
    """A design clip's emphasis: the emphasis clips starting within its span (ends included) on
    the Emphasis track just below its track. The editor moves, nudges, copies, duplicates and
    deletes them with it. Empty for any other clip."""
    track, clip = project.find_clip(clip_id)
    below = _emphasis_below(project, track.id)
    if below is None or not isinstance(project.tile(clip.tile_id), VibrationTile):
        return []
    lo = bisect_left(below.clips, clip.start, key=_start)  # a track's clips are in start order
    hi = bisect_right(below.clips, clip.end, key=_start)
    return [c.id for c in below.clips[lo:hi] if _is_emphasis(project.tile(c.tile_id))]


def with_emphasis(project: Project, clip_ids: list[str]) -> list[str]:
    """The clips followed by their designs' emphasis clips (emphasis_of), each id once."""
    chosen = list(clip_ids)
    for clip_id in clip_ids:
        chosen += emphasis_of(project, clip_id)
    return list(dict.fromkeys(chosen))


def _start(clip: Clip) -> float:
    return clip.start


def _is_emphasis(tile: object) -> bool:
    return isinstance(tile, GeneratorTile) and tile.generator == EMPHASIS


def design_of(
    project: Project, track_ids: list[str] | None = None, *, rate: float | None = None
) -> VibrationDesign:
    """The sounding drive tracks (all, or `track_ids`) as a design in timeline seconds."""
    drive = [t for t in mixer.active_tracks(project, track_ids) if t.kind == DRIVE]
    if not any(t.clips for t in drive):
        raise EditError("the project has no sounding drive track with clips")
    accents = _accents(project, drive)
    pieces: list[VibrationDesign] = []
    exact = True
    for track in drive:
        factor = _track_factor(track)
        for clip in track.clips:
            tile = project.tile(clip.tile_id)
            if clip.id in accents:
                continue
            piece = _clip_design(clip, tile, factor) if isinstance(tile, VibrationTile) else None
            if piece is None:
                exact = False
            else:
                pieces.append(piece)
    if exact and not _overlapping(pieces):
        return _joined(pieces, list(accents.values()))
    return _analysed(project, drive, accents, rate)


def _accents(project: Project, drive: list[Track]) -> dict[str, Emphasis]:
    """The drive tracks' clips read as emphasis, by clip id, in time and then placing order."""
    found = []
    for track in drive:
        factor = _track_factor(track)
        for clip in track.clips:
            accent = _as_emphasis(project.tile(clip.tile_id), clip, factor)
            if accent is not None:
                # ids count up as clips are added ("c9" before "c10"): two emphases at one time
                # keep the order they were placed in
                found.append(((accent.time, len(clip.id), clip.id), accent))
    return {key[2]: accent for key, accent in sorted(found, key=lambda item: item[0])}


def sharpness_convention(project: Project, track_ids: list[str] | None = None) -> str:
    """The AHAP sharpness convention of the first design on the drive tracks ("sqrt" if none)."""
    for track in mixer.active_tracks(project, track_ids):
        for clip in track.clips:
            tile = project.tile(clip.tile_id)
            if track.kind == DRIVE and isinstance(tile, VibrationTile):
                return tile.sharpness
    return "sqrt"


# --- exact reading of envelope clips ------------------------------------------------------------


def _track_factor(track: Track) -> float:
    """How a track scales its clips relative to the drive kind's full scale."""
    kind_scale = track_kind(track.kind).full_scale
    return track.gain * (track.full_scale or kind_scale) / kind_scale


def _as_emphasis(tile, clip: Clip, factor: float) -> Emphasis | None:
    """An emphasis clip, or a short sine-generator clip, read as an emphasis; else None."""
    if not isinstance(tile, GeneratorTile) or clip.offset != 0.0:
        return None
    if tile.generator == EMPHASIS:
        repeated = clip.stretch_mode == "repeat" and clip.stretch != 1.0
        if clip.reverse or clip.source_in != 0.0 or repeated:
            return None  # no longer the one pulse an emphasis plays
        frequency = min(1.0, max(0.0, tile.param("frequency")))
        if clip.stretch != 1.0:
            frequency = _stretched(frequency, clip.stretch)
            if frequency is None:
                return None
        level = abs(clip.gain * clip.scale * tile.param("amplitude") * factor)
        return Emphasis(clip.start, min(level, 1.0), frequency)
    if tile.generator != "sine" or clip.duration > TRANSIENT_MAX:
        return None
    level = abs(clip.gain * clip.scale * tile.param("amplitude") * factor)
    hz = tile.param("frequency") / clip.stretch
    return Emphasis(clip.start, min(level, 1.0), float(normalised_frequency(hz)))


def _stretched(f: float, stretch: float) -> float | None:
    """The normalised frequency heard after a stretch, or None outside the carrier range."""
    hz = float(carrier_hz(f)) / stretch
    if not F_MIN - 1e-9 <= hz <= F_MAX + 1e-9:
        return None
    return float(normalised_frequency(hz))


@dataclass(frozen=True)
class _Mapping:
    """How a clip maps its tile's seconds to the timeline and scales its amplitude."""

    clip: Clip
    gain: float

    def time(self, u: float) -> float:
        return self.clip.start + (u - self.clip.source_in) * self.clip.stretch

    def times(self, u: np.ndarray) -> np.ndarray:
        """`time` of each of u (the same operations, so the same bits)."""
        return self.clip.start + (u - self.clip.source_in) * self.clip.stretch

    def frequency(self, f: float) -> float | None:
        """The normalised frequency heard after a stretch, or None outside the carrier range."""
        return f if self.clip.stretch == 1.0 else _stretched(f, self.clip.stretch)

    def frequencies(self, f: np.ndarray) -> np.ndarray | None:
        """`frequency` of each of f (the same operations), or None if one is outside the range."""
        if self.clip.stretch == 1.0:
            return f
        hz = np.asarray(carrier_hz(f), dtype=np.float64) / self.clip.stretch
        if not np.all((hz >= F_MIN - 1e-9) & (hz <= F_MAX + 1e-9)):
            return None
        return normalised_frequency(hz)

    def fade(self, t: np.ndarray) -> np.ndarray:
        c = self.clip
        env = fade_envelope(np.asarray(t) - c.start, c.duration, c.fade_in, c.fade_out)
        return np.ones(np.shape(t)) if env is None else env


def _clip_design(clip: Clip, tile: VibrationTile, factor: float) -> VibrationDesign | None:
    """The clip's part of its design on the timeline, or None if edits make it not an envelope."""
    if clip.offset != 0.0 or clip.reverse or (clip.stretch_mode == "repeat" and clip.stretch != 1):
        return None
    design = tile.design
    m = _Mapping(clip, abs(clip.gain * clip.scale * factor))
    lo, hi = clip.source_in, min(clip.source_out, design.duration)
    amplitude = _cut(design.amplitude, lo, hi, outside=0.0)
    frequency = _cut(design.frequency, lo, hi, outside=None)
    heard = m.frequencies(frequency.values)
    if heard is None:
        return None
    freq = Breakpoints(m.times(frequency.times), heard)
    amp = Breakpoints(m.times(amplitude.times), np.minimum(1.0, amplitude.values * m.gain))
    faded = clip.fade_in.length > 0 or clip.fade_out.length > 0
    if faded:
        amp = breakpoints(_faded(list(amp), m))
    accents = []
    for e in design.emphasis:
        if clip.source_in <= e.time < clip.source_out:
            f = m.frequency(e.frequency)
            if f is None:
                return None
            t = m.time(e.time)
            level = e.amplitude * m.gain * (float(m.fade(np.array([t]))[0]) if faded else 1.0)
            accents.append(Emphasis(t, min(1.0, level), f))
    ends = [float(p.times[-1]) for p in (amp, freq) if len(p)]  # times ascend
    end = max([m.time(hi)] + ends + [e.time for e in accents])
    return VibrationDesign(amp, freq, tuple(accents), end)


@overload
def _cut(points: Breakpoints, lo: float, hi: float, outside: float | None) -> Breakpoints: ...
@overload
def _cut(
    points: Sequence[tuple[float, float]], lo: float, hi: float, outside: float | None
) -> list[tuple[float, float]]: ...


def _cut(points, lo: float, hi: float, outside: float | None):
    """Breakpoints within [lo, hi], with interpolated ends where the range cuts a segment:
    Breakpoints for Breakpoints, else a list of (t, v) pairs."""
    given = breakpoints(points)
    t, v = given.times, given.values
    inside = (lo <= t) & (t <= hi)
    if inside.all():
        return given if isinstance(points, Breakpoints) else list(given)

    def at(x: float) -> float:
        if outside is not None and (x < t[0] or x > t[-1]):
            return outside
        return float(np.interp(x, t, v))

    times, values = [t[inside]], [v[inside]]
    first = times[0][0] if len(times[0]) else None
    if t[0] < lo and (first is None or first > lo):
        times.insert(0, np.array([lo]))
        values.insert(0, np.array([at(lo)]))
    last = times[-1][-1] if len(times[-1]) else None
    if t[-1] > hi and (last is None or last < hi):
        times.append(np.array([hi]))
        values.append(np.array([at(hi)]))
    cut = Breakpoints(np.concatenate(times), np.concatenate(values))
    return cut if isinstance(points, Breakpoints) else list(cut)


def _faded(amp: list[tuple[float, float]], m: _Mapping) -> list[tuple[float, float]]:
    """The amplitude breakpoints times the clip's fades, reduced within EDIT_TOLERANCE.

    Every breakpoint is kept in the samples (both sides of a step), with the fade sampled every
    FADE_GRID seconds between them.
    """
    if len(amp) < 2:
        return [(t, v * float(m.fade(np.array([t]))[0])) for t, v in amp]
    bt = np.array([p[0] for p in amp])
    bv = np.array([p[1] for p in amp])
    grid = np.arange(bt[0], bt[-1], FADE_GRID)
    grid = grid[~np.isin(grid, bt)]
    t = np.concatenate([bt, grid])
    v = np.concatenate([bv, np.interp(grid, bt, bv)])
    order = np.argsort(t, kind="stable")  # breakpoints first, so steps keep their order
    t, v = t[order], v[order]
    from timeline.analysis.breakpoints import simplify

    return simplify(t, v * m.fade(t), EDIT_TOLERANCE)


def _overlapping(pieces: list[VibrationDesign]) -> bool:
    spans = sorted(_span(p) for p in pieces)
    return any(b[0] < a[1] for a, b in zip(spans, spans[1:], strict=False))


def _span(design: VibrationDesign) -> tuple[float, float]:
    times = design.amplitude.times  # ascending
    ends = [float(times[0]), float(times[-1])] if len(times) else []
    times = ends + [e.time for e in design.emphasis]
    return (min(times, default=design.duration), max(times, default=design.duration))


def _joined(pieces: list[VibrationDesign], accents: list[Emphasis]) -> VibrationDesign:
    """Non-overlapping pieces as one design, silent between them; extra accents added."""
    pieces = sorted(pieces, key=_span)
    if len(pieces) == 1 and not accents:
        return pieces[0]
    amplitude: list[np.ndarray] = []  # times and values in turn
    frequency: list[np.ndarray] = []
    for k, piece in enumerate(pieces):
        t, v = piece.amplitude.times, piece.amplitude.values
        if len(t) and k > 0 and v[0] > 0:
            t, v = np.concatenate([t[:1], t]), np.concatenate([[0.0], v])
        if len(t) and k < len(pieces) - 1 and v[-1] > 0:
            t, v = np.concatenate([t, t[-1:]]), np.concatenate([v, [0.0]])
        amplitude += [t, v]
        frequency += [piece.frequency.times, piece.frequency.values]
    emphasis = [e for p in pieces for e in p.emphasis] + accents
    # emphasis clips read back exactly: the design lasts as long as its envelopes, or until the
    # last emphasis starts (to its end when there are no envelopes)
    ends = [p.duration for p in pieces] or [e.time + e.length for e in accents]
    duration = max(ends + [e.time for e in accents])
    return VibrationDesign(_concatenated(amplitude), _concatenated(frequency), emphasis, duration)


def _concatenated(arrays: list[np.ndarray]) -> Breakpoints:
    """Breakpoints from times and values arrays in turn, joined in order."""
    return Breakpoints(
        np.concatenate([np.empty(0), *arrays[0::2]]), np.concatenate([np.empty(0), *arrays[1::2]])
    )


# --- analysis of anything else ------------------------------------------------------------------


def _analysed(
    project: Project, drive: list[Track], accents: dict[str, Emphasis], rate: float | None
) -> VibrationDesign:
    """Render the drive tracks (emphasis clips apart) and analyse them into breakpoints."""
    from timeline.analysis.breakpoints import clip_points, envelope_breakpoints, trim_silence

    rate = float(rate or project.rate or DEFAULT_TIME_RATE)
    rest = edits.remove_clips(project, list(accents))
    duration = max(c.end for t in drive for c in t.clips)
    layer = mixer.render(rest, 0.0, duration, rate, "normal", [t.id for t in drive]).get(DRIVE)
    if layer is None or not np.any(layer):
        amp, freq = [(0.0, 0.0), (duration, 0.0)], [(0.0, DEFAULT_FREQUENCY)]
    else:
        amp, freq = envelope_breakpoints(layer / track_kind(DRIVE).full_scale, rate)
        amp = trim_silence(amp)
        freq = clip_points(freq, amp[0][0], amp[-1][0])
    amp = [(t, round(v, 6)) for t, v in amp]
    freq = [(t, round(v, 6)) for t, v in freq]
    return VibrationDesign(tuple(amp), tuple(freq), tuple(accents.values()), duration)
