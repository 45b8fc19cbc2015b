"""The project state: immutable tracks, clips, tiles, palette and variants.

Every edit (timeline.edits) returns a new Project; unchanged parts are shared, so undo history
and A/B variants are cheap snapshots of the same states.
"""

from __future__ import annotations

import math
from bisect import bisect_left, insort
from collections.abc import Iterable
from dataclasses import dataclass, field, replace
from functools import cached_property
from types import MappingProxyType
from typing import Any

from immutables import Map

from timeline.errors import EditError, finite
from timeline.model.id_sequence import IdSequence
from timeline.model.markers import LoopRegion, Marker
from timeline.model.picture import project_svg
from timeline.tiles import Tile

AXES = ("time", "position")
FADE_SHAPES = ("linear", "equal-power", "exponential", "s-curve")
STRETCH_MODES = ("squeeze", "repeat")
DEFAULT_TIME_RATE = 10_000.0  # Hz: the paper's knob servo rate
DEFAULT_POSITION_RATE = 180.0 / math.pi / 0.01  # samples per radian: one every 0.01 degree
_FEW_CHANGES = 64  # clips gone and come beyond which a new track sorts its clips' ends anew


@dataclass(frozen=True)
class Fade:
    """A fade's length (axis units) and shape."""

    length: float = 0.0
    shape: str = "linear"

    def __post_init__(self) -> None:
        if self.length == 0.0 and type(self.length) is float and self.shape == "linear":
            return  # no fade: the common case, nothing to check
        length = finite("a fade's length", self.length)
        if length < 0:
            raise EditError(f"a fade's length cannot be negative ({length})")
        if self.shape not in FADE_SHAPES:
            raise EditError(
                f"unknown fade shape {self.shape!r} (choose from {', '.join(FADE_SHAPES)})"
            )
        object.__setattr__(self, "length", length)


_CLIP_NUMBERS = ("start", "source_in", "source_out", "stretch", "loop_phase", "gain", "scale",
                 "offset", "pivot")  # fmt: skip


@dataclass(frozen=True)
class Clip:
    """A tile placed on a track.

    The clip plays source [source_in, source_out) of its tile. Its length on the timeline is
    (source_out - source_in) * stretch: in `squeeze` mode the source is resampled (a 10 Hz sine
    stretched by 2 plays at 5 Hz); in `repeat` mode it loops at its own speed, `loop_phase` into
    the loop. Amplitude: value = gain * (scale * shape + offset), where scaling by f about a
    horizontal mirror line p maps y to p + f*(y - p); `pivot` is the line the user placed.
    """

    id: str
    tile_id: str
    start: float
    source_in: float
    source_out: float
    stretch: float = 1.0
    stretch_mode: str = "squeeze"
    loop_phase: float = 0.0
    gain: float = 1.0
    scale: float = 1.0
    offset: float = 0.0
    pivot: float = 0.0
    reverse: bool = False
    fade_in: Fade = Fade()
    fade_out: Fade = Fade()

    def __post_init__(self) -> None:
        for name in _CLIP_NUMBERS:
            value = getattr(self, name)
            if type(value) is not float or not math.isfinite(value):  # the message only if bad
                object.__setattr__(self, name, finite(f"a clip's {name.replace('_', ' ')}", value))
        self._check_ranges()

    @classmethod
    def from_checked(cls, values: dict[str, Any]) -> Clip:
        """A clip from a dict of all its fields whose numbers are already finite floats and whose
        fades are Fades (a file reader's fast path): only the rules between fields are checked,
        with the same EditError as the constructor."""
        clip = object.__new__(cls)
        clip.__dict__.update(values)
        clip._check_ranges()
        return clip

    def _check_ranges(self) -> None:
        if self.source_out <= self.source_in:
            raise EditError("a clip must play a source range of positive length")
        if self.stretch <= 0:
            raise EditError(f"a clip's stretch must be positive, not {self.stretch}")
        if self.stretch_mode not in STRETCH_MODES:
            raise EditError(f"unknown stretch mode {self.stretch_mode!r} (squeeze or repeat)")
        if not math.isfinite(self.end):
            raise EditError(
                f"a clip starting at {self.start:g} and lasting {self.duration:g} ends beyond "
                "any finite time"
            )

    @property
    def source_length(self) -> float:
        return self.source_out - self.source_in

    @property
    def duration(self) -> float:
        return self.source_length * self.stretch

    @property
    def end(self) -> float:
        return self.start + self.duration

    @property
    def inverted(self) -> bool:
        """True when the clip is mirrored (its amplitude scale is negative)."""
        return self.scale < 0


@dataclass(frozen=True)
class Track:
    """One haptic layer: a kind (its meaning), gain, mute/solo and the clips on it."""

    id: str
    kind: str
    name: str
    clips: tuple[Clip, ...] = ()
    gain: float = 1.0
    mute: bool = False
    solo: bool = False
    full_scale: float | None = None  # None: the kind's full scale

    def clip(self, clip_id: str) -> Clip:
        found = self.clips_by_id.get(clip_id)
        if found is None:
            raise EditError(f"track {self.name!r} has no clip {clip_id!r}")
        return found

    @cached_property
    def clips_by_id(self) -> dict[str, Clip]:
        """Clip id -> clip, built once per track state (edits share unchanged tracks)."""
        return {c.id: c for c in self.clips}

    @cached_property
    def _starts(self) -> tuple[list[float], float] | None:
        """Clip starts and the longest clip, if the clips are in start order (else None)."""
        starts = [c.start for c in self.clips]
        if any(b < a for a, b in zip(starts, starts[1:], strict=False)):
            return None
        return starts, max((c.duration for c in self.clips), default=0.0)

    def clips_between(self, t0: float, t1: float, margin: float) -> tuple[Clip, ...]:
        """The clips that may overlap [t0 - margin, t1 + margin), in track order (a superset).

        Found by bisection when the clips are in start order (edits keep them so), so a render of
        a short window does not visit every clip of a long track.
        """
        found = self._starts
        if found is None:
            return self.clips
        starts, longest = found
        first = bisect_left(starts, t0 - longest - margin)
        return self.clips[first : bisect_left(starts, t1 + margin)]

    @cached_property
    def _ends(self) -> list[float]:
        """The clips' ends in ascending order (a track made by `with_clips` gets them from the
        track it came from, not from a walk over its clips)."""
        return sorted(c.end for c in self.clips)

    @property
    def end(self) -> float:
        """End of the track's last-ending clip (0 for an empty track)."""
        ends = self._ends
        return ends[-1] if ends else 0.0

    def with_clips(
        self, clips: tuple[Clip, ...], gone: Iterable[Clip] = (), came: Iterable[Clip] = ()
    ) -> Track:
        """This track holding `clips`, which are its clips less `gone` plus `came`.

        When this track's ends are known, the new track's are them less the ends of `gone` plus
        those of `came` (bisection, and a copy of a list of floats), so moving one clip of a
        long track does not walk its clips to find where the track ends.
        """
        track = replace(self, clips=clips)
        known = self.__dict__.get("_ends")
        gone, came = list(gone), list(came)
        if known is None or len(gone) + len(came) > _FEW_CHANGES:
            return track
        ends = list(known)
        for clip in gone:
            at = bisect_left(ends, clip.end)
            if at == len(ends) or ends[at] != clip.end:
                return track  # not one of this track's clips: the new track finds its own
            del ends[at]
        for clip in came:
            insort(ends, clip.end)
        track.__dict__["_ends"] = ends
        return track


@dataclass(frozen=True)
class PaletteTab:
    """A palette tab: templates, scratch, or a user collection of tile ids."""

    name: str
    role: str  # "templates", "scratch" or "user"
    tile_ids: IdSequence = IdSequence()  # any iterable of ids is kept as an IdSequence

    def __post_init__(self) -> None:
        object.__setattr__(self, "tile_ids", IdSequence.of(self.tile_ids))


@dataclass(frozen=True)
class Variant:
    """A named snapshot of a design (tracks and tiles), for A/B comparison by feel."""

    name: str
    tracks: tuple[Track, ...]
    tiles: Map

    def __post_init__(self) -> None:
        object.__setattr__(self, "tiles", _tile_map(self.tiles))


def _frozen_map(mapping: Any) -> MappingProxyType:
    return mapping if isinstance(mapping, MappingProxyType) else MappingProxyType(dict(mapping))


def map_changes(old: Map, new: Map) -> tuple[dict[str, Any], tuple[str, ...]]:
    """The entries of `new` that are not the same object in `old` (the model is immutable, so an
    unchanged entry is the same object), and the keys of `old` that `new` lacks."""
    changed = {k: v for k, v in new.items() if old.get(k) is not v}
    return changed, tuple(k for k in old if k not in new)


def _tile_map(mapping: Any) -> Map:
    """Tiles by id as a persistent map: adding one to 16,000 shares the rest (O(log n))."""
    return mapping if isinstance(mapping, Map) else Map(dict(mapping))


@dataclass(frozen=True)
class Project:
    """A whole design: axis, rate, tracks, tile library, palette, variants, markers, loop region
    and metadata."""

    axis: str = "time"
    rate: float = DEFAULT_TIME_RATE
    tracks: tuple[Track, ...] = ()
    tiles: Map = field(default_factory=Map)
    palette: tuple[PaletteTab, ...] = (
        PaletteTab("Templates", "templates"),
        PaletteTab("Scratch", "scratch"),
    )
    variants: tuple[Variant, ...] = ()
    active_variant: str | None = None
    metadata: MappingProxyType = field(default_factory=lambda: MappingProxyType({}))
    next_id: int = 1
    markers: tuple[Marker, ...] = ()  # sorted by position (timeline.edits.markers edits them)
    loop: LoopRegion | None = None

    def __post_init__(self) -> None:
        if self.axis not in AXES:
            raise EditError(f"unknown axis {self.axis!r} (choose time or position)")
        rate = finite("the project's rate", self.rate)
        if rate <= 0:
            raise EditError(f"the project's rate must be positive, not {rate}")
        object.__setattr__(self, "rate", rate)
        object.__setattr__(self, "tiles", _tile_map(self.tiles))
        object.__setattr__(self, "metadata", _frozen_map(self.metadata))

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Project):
            return NotImplemented
        return all(
            (dict(getattr(self, f)) if f in ("tiles", "metadata") else getattr(self, f))
            == (dict(getattr(other, f)) if f in ("tiles", "metadata") else getattr(other, f))
            for f in self.__dataclass_fields__
        )

    __hash__ = None  # type: ignore[assignment]

    @property
    def unit(self) -> str:
        """The axis unit: seconds for time, radians for position."""
        return "s" if self.axis == "time" else "rad"

    @cached_property
    def duration(self) -> float:
        """End of the last clip on any track (0 for an empty project)."""
        return max((t.end for t in self.tracks if t.clips), default=0.0)

    def track(self, track_id: str) -> Track:
        for t in self.tracks:
            if t.id == track_id:
                return t
        raise EditError(f"there is no track {track_id!r}")

    def tile(self, tile_id: str) -> Tile:
        try:
            return self.tiles[tile_id]
        except KeyError:
            raise EditError(f"there is no tile {tile_id!r}") from None

    def find_clip(self, clip_id: str) -> tuple[Track, Clip]:
        for t in self.tracks:
            c = t.clips_by_id.get(clip_id)
            if c is not None:
                return t, c
        raise EditError(f"there is no clip {clip_id!r}")

    def tab(self, name: str) -> PaletteTab:
        for tab in self.palette:
            if tab.name == name:
                return tab
        raise EditError(f"there is no palette tab {name!r}")

    def variant(self, name: str) -> Variant:
        for v in self.variants:
            if v.name == name:
                return v
        raise EditError(f"there is no variant {name!r}")

    def _repr_svg_(self) -> str:
        """The timeline as a picture: what a notebook shows (timeline.model.picture)."""
        return project_svg(self)

    def with_id(self, prefix: str) -> tuple[Project, str]:
        """Return a project with its id counter advanced, and a fresh id with the prefix."""
        return replace(self, next_id=self.next_id + 1), f"{prefix}{self.next_id}"
