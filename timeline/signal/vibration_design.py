"""A vibrotactile design as data: amplitude and frequency envelopes, emphasis, and its carrier.

This is what .haptic and AHAP files hold and what `convert` makes. Times are seconds from the
design's start; amplitude is 0..1 of full scale; frequency is normalised 0..1 as in .haptic and
maps linearly to a carrier of F_MIN..F_MAX Hz. The carrier is synthesised only when rendering
(`VibrationDesign.render`), exactly at any time: its phase is the closed-form integral of the
piecewise-linear frequency envelope. No Qt, no plugins, no timeline model.

Rendering conventions (ours; players differ): the amplitude envelope is linear between
breakpoints and zero outside the first and last; the frequency envelope is linear between
breakpoints and holds its end values (0.5 when there is none); an emphasis is a pulse of
EMPHASIS_CYCLES carrier cycles at its own amplitude and frequency, full for the first cycle and
fading linearly over the second (`emphasis_pulse`), added to the continuous carrier the way an
emphasis clip on the timeline adds to the clips under it (the analysis lowers the envelope under
an emphasis instead: its ducking).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass
from typing import Any, overload

import numpy as np

from timeline.errors import EditError

F_MIN = 80.0  # Hz at normalised frequency 0
F_MAX = 230.0  # Hz at normalised frequency 1
DEFAULT_FREQUENCY = 0.5  # normalised frequency assumed when a design has no frequency envelope
EMPHASIS_CYCLES = 2

_ITER_CHUNK = 4096  # breakpoints made into Python floats at a time while iterating


def carrier_hz(frequency: np.ndarray | float) -> np.ndarray | float:
    """The carrier frequency (Hz) for a normalised frequency in 0..1."""
    return F_MIN + np.clip(frequency, 0.0, 1.0) * (F_MAX - F_MIN)


@overload
def normalised_frequency(hz: np.ndarray) -> np.ndarray: ...
@overload
def normalised_frequency(hz: float) -> float: ...


def normalised_frequency(hz: np.ndarray | float) -> np.ndarray | float:
    """The normalised frequency (0..1) of a carrier frequency, clipped to the mapped range."""
    return np.clip((np.asarray(hz, dtype=np.float64) - F_MIN) / (F_MAX - F_MIN), 0.0, 1.0)


def _unit(value: float, what: str) -> float:
    value = float(value)
    if not (math.isfinite(value) and 0.0 <= value <= 1.0):
        raise EditError(f"{what} must be between 0 and 1, not {value!r}")
    return value


class Breakpoints(Sequence[tuple[float, float]]):
    """(time, value) breakpoints held as two read-only float64 arrays, `times` and `values`.

    Read like the tuple of (t, v) pairs it stands for: indexing, iterating and comparing give
    Python floats (made a chunk at a time while iterating, never one object per breakpoint held),
    a slice is Breakpoints, and `np.asarray` gives the (n, 2) array. Made by `breakpoints()`.
    """

    __slots__ = ("times", "values")
    times: np.ndarray
    values: np.ndarray

    def __init__(self, times: np.ndarray, values: np.ndarray) -> None:
        for name, array in (("times", times), ("values", values)):
            array = np.ascontiguousarray(array, dtype=np.float64)
            array.setflags(write=False)
            object.__setattr__(self, name, array)

    def __setattr__(self, name: str, value: Any) -> None:
        raise AttributeError("breakpoints are read-only")

    def __reduce__(self) -> tuple[Any, ...]:
        return (Breakpoints, (self.times, self.values))

    def __len__(self) -> int:
        return len(self.times)

    @overload
    def __getitem__(self, k: int) -> tuple[float, float]: ...
    @overload
    def __getitem__(self, k: slice) -> Breakpoints: ...

    def __getitem__(self, k: int | slice) -> tuple[float, float] | Breakpoints:
        if isinstance(k, slice):
            return Breakpoints(self.times[k], self.values[k])
        return (self.times.item(k), self.values.item(k))

    def __iter__(self) -> Iterator[tuple[float, float]]:
        for first in range(0, len(self.times), _ITER_CHUNK):
            chunk = slice(first, first + _ITER_CHUNK)
            yield from zip(self.times[chunk].tolist(), self.values[chunk].tolist(), strict=True)

    def __array__(self, dtype: Any = None, copy: Any = None) -> np.ndarray:
        pairs = np.column_stack([self.times, self.values]) if len(self) else np.empty((0, 2))
        return pairs if dtype is None else pairs.astype(dtype)

    def __eq__(self, other: object) -> bool:
        if isinstance(other, Breakpoints):
            return np.array_equal(self.times, other.times) and np.array_equal(
                self.values, other.values
            )
        if isinstance(other, tuple):
            return tuple(self) == other
        return NotImplemented

    def __hash__(self) -> int:
        return hash(((self.times + 0.0).tobytes(), (self.values + 0.0).tobytes()))  # -0.0 as 0.0

    def __add__(self, other: Sequence[tuple[float, float]]) -> tuple[tuple[float, float], ...]:
        return tuple(self) + tuple(other)

    def __radd__(self, other: Sequence[tuple[float, float]]) -> tuple[tuple[float, float], ...]:
        return tuple(other) + tuple(self)

    def __repr__(self) -> str:
        return f"Breakpoints({tuple(self)!r})"

    def shifted(self, offset: float) -> Breakpoints:
        """The same breakpoints `offset` seconds later."""
        return Breakpoints(self.times + offset, self.values)


def breakpoints(points: Any, what: str = "the") -> Breakpoints:
    """Checked breakpoints from (t, v) pairs, an (n, 2) array or Breakpoints (checked, kept as
    they are): times finite, >= 0 and in order, values in 0..1; else an EditError naming the
    first bad one."""
    if isinstance(points, Breakpoints):
        t, v = points.times, points.values
    else:
        rows = points if isinstance(points, np.ndarray) else tuple(points)
        try:
            array = np.array(rows, dtype=np.float64).reshape(len(rows), 2)
        except (TypeError, ValueError):
            raise EditError(f"{what} breakpoints must be (time, value) pairs of numbers") from None
        t, v = array[:, 0], array[:, 1]
    bad_time = ~(np.isfinite(t) & (t >= 0.0))
    if bad_time.any():
        k = int(np.flatnonzero(bad_time)[0])
        raise EditError(f"{what} breakpoint {k + 1} has time {t[k]!r}; it must be >= 0 s")
    backwards = np.flatnonzero(np.diff(t) < 0)
    if len(backwards):
        k = int(backwards[0]) + 1
        raise EditError(f"{what} breakpoint {k + 1} goes back in time ({t[k]:g} s)")
    bad_value = ~(np.isfinite(v) & (v >= 0.0) & (v <= 1.0))
    if bad_value.any():
        k = int(np.flatnonzero(bad_value)[0])
        raise EditError(f"{what} breakpoint {k + 1}'s value must be between 0 and 1, not {v[k]!r}")
    return points if isinstance(points, Breakpoints) else Breakpoints(t, v)


@dataclass(frozen=True)
class Emphasis:
    """A short accent at `time` (s) with its own amplitude and normalised frequency (0..1)."""

    time: float
    amplitude: float
    frequency: float

    def __post_init__(self) -> None:
        time = float(self.time)
        if not (math.isfinite(time) and time >= 0.0):
            raise EditError(f"an emphasis time must be a number >= 0 s, not {self.time!r}")
        object.__setattr__(self, "time", time)
        object.__setattr__(self, "amplitude", _unit(self.amplitude, "an emphasis amplitude"))
        object.__setattr__(self, "frequency", _unit(self.frequency, "an emphasis frequency"))

    @property
    def length(self) -> float:
        """Seconds the emphasis pulse lasts (EMPHASIS_CYCLES cycles of its carrier)."""
        return emphasis_length(self.frequency)


def emphasis_length(frequency: float) -> float:
    """Seconds an emphasis of normalised frequency `frequency` lasts (EMPHASIS_CYCLES cycles)."""
    # carrier_hz in plain floats (the same operations, so the same bits): numpy's clip costs
    # 10 us a call, and an import of 10,000 transients asks 20,000 times.
    hz = F_MIN + min(max(float(frequency), 0.0), 1.0) * (F_MAX - F_MIN)
    return EMPHASIS_CYCLES / hz


def emphasis_pulse(d: np.ndarray, amplitude: float, frequency: float) -> np.ndarray:
    """An emphasis pulse `d` seconds after it starts: EMPHASIS_CYCLES cycles of the carrier for
    normalised `frequency`, full for the first cycle, fading linearly over the rest; 0 outside."""
    d = np.asarray(d, dtype=np.float64)
    hz = float(carrier_hz(frequency))
    length = EMPHASIS_CYCLES / hz
    fade = np.clip(EMPHASIS_CYCLES * (1.0 - d / length), 0.0, 1.0)
    inside = (d >= 0.0) & (d < length)
    return np.where(inside, amplitude * fade * np.sin(2.0 * np.pi * hz * d), 0.0)


@dataclass(frozen=True, init=False)
class VibrationDesign:
    """Amplitude and frequency breakpoints (seconds, 0..1; held as `Breakpoints`, float64 arrays,
    whatever they are given as), emphasis, and the design's length."""

    amplitude: Breakpoints
    frequency: Breakpoints
    emphasis: tuple[Emphasis, ...]
    duration: float

    def __init__(
        self,
        amplitude: Breakpoints | np.ndarray | Iterable[tuple[float, float]],
        frequency: Breakpoints | np.ndarray | Iterable[tuple[float, float]],
        emphasis: Iterable[Emphasis | tuple[float, float, float]],
        duration: float,
    ) -> None:
        """Checked breakpoints (`breakpoints`), emphasis in time order ((time, amplitude,
        frequency) tuples are welcome), and a positive duration reaching past them all."""
        checked_amplitude = breakpoints(amplitude, "amplitude")
        checked_frequency = breakpoints(frequency, "frequency")
        accents = tuple(e if isinstance(e, Emphasis) else Emphasis(*e) for e in emphasis)
        accents = tuple(sorted(accents, key=lambda e: e.time))
        length = float(duration)
        if not (math.isfinite(length) and length > 0.0):
            raise EditError(f"a vibration design must last a positive time, not {length!r} s")
        ends = [float(p.times[-1]) for p in (checked_amplitude, checked_frequency) if len(p)]
        latest = max(ends + [e.time for e in accents], default=0.0)  # times ascend
        if latest > length:
            raise EditError(f"a vibration design of {length:g} s has a breakpoint at {latest:g} s")
        object.__setattr__(self, "amplitude", checked_amplitude)
        object.__setattr__(self, "frequency", checked_frequency)
        object.__setattr__(self, "emphasis", accents)
        object.__setattr__(self, "duration", length)

    @property
    def extent(self) -> float:
        """Seconds the design sounds for: its duration, or longer if an emphasis rings past it."""
        return max([self.duration] + [e.time + e.length for e in self.emphasis])

    def shifted(self, offset: float, duration: float | None = None) -> VibrationDesign:
        """The same design `offset` seconds later (duration grows by the offset by default)."""
        return VibrationDesign(
            self.amplitude.shifted(offset),
            self.frequency.shifted(offset),
            tuple(Emphasis(e.time + offset, e.amplitude, e.frequency) for e in self.emphasis),
            self.duration + offset if duration is None else duration,
        )

    def amplitude_at(self, u: np.ndarray) -> np.ndarray:
        """The amplitude envelope at times u: linear between breakpoints, zero outside them."""
        u = np.asarray(u, dtype=np.float64)
        if not self.amplitude:
            return np.zeros(u.shape)
        t, v = self.amplitude.times, self.amplitude.values
        return np.where((u < t[0]) | (u > t[-1]), 0.0, np.interp(u, t, v))

    def frequency_at(self, u: np.ndarray) -> np.ndarray:
        """The normalised frequency at times u, holding the end values outside the breakpoints."""
        u = np.asarray(u, dtype=np.float64)
        if not self.frequency:
            return np.full(u.shape, DEFAULT_FREQUENCY)
        return np.interp(u, self.frequency.times, self.frequency.values)

    def cycles(self, u: np.ndarray) -> np.ndarray:
        """Carrier cycles elapsed from time 0 to each u (the exact integral of its frequency)."""
        u = np.asarray(u, dtype=np.float64)
        points = self.frequency or Breakpoints(np.zeros(1), np.full(1, DEFAULT_FREQUENCY))
        t = points.times
        hz = np.asarray(carrier_hz(points.values), dtype=np.float64)
        width = np.diff(t)
        at_knots = hz[0] * t[0] + np.concatenate(
            [[0.0], np.cumsum(0.5 * (hz[:-1] + hz[1:]) * width)]
        )
        k = np.searchsorted(t, u, side="right") - 1
        before = k < 0
        k = np.clip(k, 0, len(t) - 1)
        d = u - t[k]
        slope = np.zeros(len(t))
        inner = width > 0
        with np.errstate(over="ignore"):
            slope[:-1][inner] = (hz[1:][inner] - hz[:-1][inner]) / width[inner]
        # A segment too narrow for its slope to be a float (a denormal width) adds under 1e-300
        # cycles through the slope: it is held flat, so the knot's own sample is not 0 * inf.
        slope[~np.isfinite(slope)] = 0.0
        slope[-1] = 0.0
        out = at_knots[k] + hz[k] * d + 0.5 * slope[k] * d * d
        return np.where(before, hz[0] * u, out)

    def render(self, u: np.ndarray) -> np.ndarray:
        """The drive waveform (fraction of full scale) at times u; zero outside [0, extent]."""
        u = np.asarray(u, dtype=np.float64)
        phase = np.mod(self.cycles(u), 1.0)
        out = self.amplitude_at(u) * np.sin(2.0 * np.pi * phase)
        for e in self.emphasis:
            out += emphasis_pulse(u - e.time, e.amplitude, e.frequency)
        return np.where((u < 0.0) | (u > self.extent), 0.0, out)
