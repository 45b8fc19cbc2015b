"""Tiles: unitless shapes over an axis (seconds or radians) that clips place on tracks.

A tile has no physical meaning of its own; a track kind gives it one (the paper's palette).
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

import numpy as np

from timeline.errors import EditError
from timeline.signal import samples
from timeline.signal.band_limit import band_limited
from timeline.signal.generators import GENERATORS
from timeline.signal.grid_shapes import generator_on_grid, spline_on_grid
from timeline.signal.render_presets import QualityPreset
from timeline.signal.resample import sample_grid
from timeline.signal.splines import PiecewiseCubic, natural_cubic, pchip
from timeline.tiles.vibration_tile import VibrationTile

MAX_TILE_SAMPLES = 2**31  # ~16 GiB of float64; anything larger is refused as a hostile size
# A sampled tile's rate (samples per second or per radian): from one sample every 1,000 units to
# 1e9 per unit (beyond any recording); outside, a renderer's work grows with the ratio to the
# output rate, not with what the output needs (docs/reliability.md).
MIN_SAMPLE_RATE = 1e-3
MAX_SAMPLE_RATE = 1e9


def _check_duration(duration: float) -> float:
    duration = float(duration)
    if not math.isfinite(duration) or duration <= 0:
        raise EditError(f"a tile's duration must be a positive number, not {duration!r}")
    return duration


def _number(generator: str, name: str, value: Any) -> float:
    """A generator parameter as a float, or an EditError naming it."""
    try:
        return float(value)
    except (TypeError, ValueError, OverflowError):
        raise EditError(
            f"generator {generator!r} parameter {name!r} must be a number, not {value!r}"
        ) from None


def _evaluate_decimated(fn, u0: float, du: float, n: int, decimation: int) -> np.ndarray:
    """Evaluate fn(u, lo, hi) on every `decimation`-th grid point and interpolate linearly in
    between; lo, hi are the grid's least and greatest u (its ends: a grid is monotone)."""
    every = decimation <= 1 or n <= 2 * decimation
    if every:  # u0 + du * i built in place: the same bits without two temporaries
        u = np.arange(n, dtype=np.float64)
        u *= du
        u += u0
    else:
        at = np.arange(0, n + decimation - 1, decimation)
        at[-1] = min(at[-1], n - 1)
        u = u0 + du * at
    ends = (float(u[0]), float(u[-1])) if u.size else (0.0, 0.0)
    values = fn(u, min(ends), max(ends))
    return values if every else np.interp(np.arange(n), at, values)


def _range(u: np.ndarray) -> tuple[float, float]:
    """The least and greatest of any u ((0, 0) when empty)."""
    return (float(u.min()), float(u.max())) if u.size else (0.0, 0.0)


def _zero_outside(u: np.ndarray, values: np.ndarray, duration: float, lo: float,
                  hi: float) -> np.ndarray:  # fmt: skip
    """values where 0 <= u <= duration, else 0 (lo, hi: the range of u), shaped like u."""
    if lo < 0 or hi > duration or values.shape != u.shape:
        return np.where((u < 0) | (u > duration), 0.0, values)
    return values


@dataclass(frozen=True, eq=False)
class SampledTile:
    """Samples at a rate (imports, merges, freehand drawing); sample k sits at k/rate.

    The samples are float64, or float32 when a reader has stored values that are all float32
    exactly (timeline.signal.samples); renders read them as float64 either way.
    """

    data: np.ndarray
    rate: float
    name: str = "sampled"
    source: str = ""  # where it came from (file name), for the user's information

    def __post_init__(self) -> None:
        data = self.data
        if not samples.frozen(data):  # anything another owner could change is copied
            data = np.array(np.reshape(data, -1), dtype=np.float64)  # its own memory: frozen
        if data.size == 0:
            raise EditError("a sampled tile needs at least one sample")
        if data.size > MAX_TILE_SAMPLES:
            raise EditError(f"a sampled tile of {data.size} samples is larger than supported")
        bad = samples.first_non_finite(data)
        if bad is not None:
            raise EditError(f"sample {bad} of tile {self.name!r} is not a finite number")
        self._keep(data)

    @classmethod
    def from_checked(
        cls, data: np.ndarray, rate: float, name: str, source: str, key: str | None = None
    ) -> SampledTile:
        """A tile from a frozen array (timeline.signal.samples.frozen) already checked finite,
        with its content key if the caller computed it while reading: an hour's samples are not
        scanned again."""
        if not samples.frozen(data) or data.size == 0 or data.size > MAX_TILE_SAMPLES:
            raise EditError("a checked sampled tile needs a reader's own read-only samples")
        tile = object.__new__(cls)
        object.__setattr__(tile, "data", data)
        object.__setattr__(tile, "rate", rate)
        object.__setattr__(tile, "name", name)
        object.__setattr__(tile, "source", source)
        tile._keep(data)
        if key is not None:
            tile.__dict__["key"] = key
        return tile

    def _keep(self, data: np.ndarray) -> None:
        rate = float(self.rate)
        if not math.isfinite(rate) or rate <= 0:
            raise EditError(f"a sampled tile's rate must be a positive number, not {self.rate!r}")
        if not MIN_SAMPLE_RATE <= rate <= MAX_SAMPLE_RATE:
            raise EditError(
                f"a sampled tile's rate must be from {MIN_SAMPLE_RATE:g} to {MAX_SAMPLE_RATE:g} "
                f"samples per second (or radian), not {rate:g}"
            )
        data.setflags(write=False)
        object.__setattr__(self, "data", data)
        object.__setattr__(self, "rate", rate)

    @property
    def duration(self) -> float:
        return len(self.data) / self.rate

    @property
    def reverse_shift(self) -> float:
        """Reversal maps sample k to sample n-1-k, so it is shifted by one sample period."""
        return 1.0 / self.rate

    @cached_property
    def key(self) -> str:
        return samples.content_key(self.data, self.rate)

    def render(self, u0: float, du: float, n: int, quality: QualityPreset) -> np.ndarray:
        return sample_grid(self.data, self.rate, u0, du, n, quality)

    def with_name(self, name: str) -> SampledTile:
        """The same samples (no new scan or hash) under another name."""
        key = self.__dict__.get("key")
        return SampledTile.from_checked(self.data, self.rate, name, self.source, key)

    def __eq__(self, other: object) -> bool:
        return (
            isinstance(other, SampledTile)
            and self.rate == other.rate
            and self.name == other.name
            and self.source == other.source
            and self.data.dtype == other.data.dtype
            and np.array_equal(self.data, other.data)
        )

    def __hash__(self) -> int:
        return hash(self.key)


@dataclass(frozen=True)
class SplineTile:
    """Control points (t, v) joined by a natural cubic spline or a monotone (PCHIP) curve."""

    points: tuple[tuple[float, float], ...]
    duration: float
    method: str = "natural"  # "natural" or "pchip"
    name: str = "spline"

    def __post_init__(self) -> None:
        pts = tuple(sorted((float(t), float(v)) for t, v in self.points))
        if not pts:
            raise EditError("a spline tile needs at least one control point")
        if not all(math.isfinite(t) and math.isfinite(v) for t, v in pts):
            raise EditError("spline control points must be finite numbers")
        if len({t for t, _ in pts}) != len(pts):
            raise EditError("two spline control points cannot share one time")
        if self.method not in ("natural", "pchip"):
            raise EditError(f"unknown spline method {self.method!r} (choose natural or pchip)")
        object.__setattr__(self, "points", pts)
        object.__setattr__(self, "duration", _check_duration(self.duration))

    reverse_shift = 0.0

    @property
    def key(self) -> str:
        return "spline:" + repr((self.points, self.duration, self.method))

    @cached_property
    def _curve(self):
        t = np.array([p[0] for p in self.points])
        v = np.array([p[1] for p in self.points])
        if len(t) == 1:
            return lambda u: np.full(np.shape(u), v[0])
        if len(t) == 2:
            return lambda u: np.interp(u, t, v)
        return pchip(t, v) if self.method == "pchip" else natural_cubic(t, v)

    def evaluate(self, u: np.ndarray) -> np.ndarray:
        """Exact curve values; before the first point and after the last the end values hold."""
        u = np.asarray(u, dtype=np.float64)
        return self._values(u, *_range(u))

    def _values(self, u: np.ndarray, lo: float, hi: float, grid: bool = False) -> np.ndarray:
        """evaluate(u) for float64 u whose least and greatest values are lo and hi (with `grid`,
        u is a render's arithmetic grid: sorted, and clipping keeps it so)."""
        first, last = self.points[0], self.points[-1]
        inside = u if first[0] <= lo and hi <= last[0] else np.clip(u, first[0], last[0])
        curve = self._curve
        out = curve(inside, grid) if isinstance(curve, PiecewiseCubic) else curve(inside)
        out = np.asarray(out, dtype=np.float64)
        # each mask only where some u needs it (a clip's grid is usually inside the curve)
        if lo <= first[0]:
            out = np.where(u <= first[0], first[1], out)
        if hi >= last[0]:
            out = np.where(u >= last[0], last[1], out)
        return _zero_outside(u, out, self.duration, lo, hi)

    def render(self, u0: float, du: float, n: int, quality: QualityPreset) -> np.ndarray:
        curve = self._curve
        if isinstance(curve, PiecewiseCubic) and (
            quality.control_decimation <= 1 or n <= 2 * quality.control_decimation
        ):
            ends = (self.points[0][1], self.points[-1][1])
            values = spline_on_grid(curve.x, curve.a, curve.b, curve.c, curve.d, ends,
                                    self.duration, u0, du, n)  # fmt: skip
            if values is not None:
                return values

        def on_grid(u: np.ndarray, lo: float, hi: float) -> np.ndarray:
            return self._values(u, lo, hi, grid=True)

        return _evaluate_decimated(on_grid, u0, du, n, quality.control_decimation)

    def with_name(self, name: str) -> SplineTile:
        return SplineTile(self.points, self.duration, self.method, name)


@dataclass(frozen=True)
class GeneratorTile:
    """A closed-form shape (sine, chirp, detents, ...) exact at any rate; zero outside its span."""

    generator: str
    duration: float
    params: tuple[tuple[str, float], ...] = field(default=())
    name: str = ""

    def __post_init__(self) -> None:
        if self.generator not in GENERATORS:
            raise EditError(
                f"unknown generator {self.generator!r} (choose from {', '.join(GENERATORS)})"
            )
        spec = GENERATORS[self.generator]
        given = dict(self.params)
        unknown = set(given) - set(spec.defaults)
        if unknown:
            raise EditError(
                f"generator {self.generator!r} has no parameter {sorted(unknown)[0]!r} "
                f"(it takes {', '.join(spec.defaults)})"
            )
        merged = {**spec.defaults, **{k: _number(self.generator, k, v) for k, v in given.items()}}
        for name, value in merged.items():
            if not math.isfinite(value):
                raise EditError(
                    f"generator {self.generator!r} parameter {name!r} must be a finite number, "
                    f"not {value!r}"
                )
        object.__setattr__(self, "params", tuple(sorted(merged.items())))
        object.__setattr__(self, "duration", _check_duration(self.duration))
        problem = spec.check(merged, self.duration) if spec.check else None
        if problem:
            raise EditError(problem)
        if not self.name:
            object.__setattr__(self, "name", self.generator)

    reverse_shift = 0.0

    @property
    def key(self) -> str:
        return "gen:" + json.dumps([self.generator, self.duration, self.params])

    def param(self, name: str) -> float:
        return dict(self.params)[name]

    def evaluate(self, u: np.ndarray) -> np.ndarray:
        """Exact values at positions u; zero outside [0, duration]."""
        u = np.asarray(u, dtype=np.float64)
        return self._values(u, *_range(u))

    def _values(self, u: np.ndarray, lo: float, hi: float) -> np.ndarray:
        """evaluate(u) for float64 u whose least and greatest values are lo and hi."""
        with np.errstate(all="ignore"):
            values = GENERATORS[self.generator].function(u, self.duration, **dict(self.params))
        return _zero_outside(u, np.asarray(values, dtype=np.float64), self.duration, lo, hi)

    def render(self, u0: float, du: float, n: int, quality: QualityPreset) -> np.ndarray:
        """Samples on the grid u0 + k*du, with content at or above its Nyquist removed (the
        Nyquist of the grid actually evaluated, when the preset decimates)."""
        decimation = quality.control_decimation if n > 2 * quality.control_decimation else 1
        spacing = abs(du) * max(1, decimation)
        nyquist = 0.5 / spacing if spacing > 0 else math.inf
        params = dict(self.params)
        if decimation == 1:
            values = generator_on_grid(self.generator, params, self.duration, u0, du, n, nyquist)
            if values is not None:
                return values

        def shape(u: np.ndarray, lo: float, hi: float) -> np.ndarray:
            return band_limited(self.generator, u, nyquist, self.duration, params,
                                lambda v: self._values(v, lo, hi), (lo, hi))  # fmt: skip

        return _evaluate_decimated(shape, u0, du, n, quality.control_decimation)

    def with_name(self, name: str) -> GeneratorTile:
        return GeneratorTile(self.generator, self.duration, self.params, name)


Tile = SampledTile | SplineTile | GeneratorTile | VibrationTile


def generator(name: str, duration: float, title: str = "", **params: Any) -> GeneratorTile:
    """Make a generator tile, e.g. generator("sine", 1.0, frequency=10)."""
    return GeneratorTile(name, duration, tuple(params.items()), title)


def spline(
    points: list[tuple[float, float]],
    duration: float | None = None,
    method: str = "natural",
    name: str = "spline",
) -> SplineTile:
    """Make a spline tile from control points; duration defaults to the last point's time."""
    if duration is None:
        duration = max(t for t, _ in points) if points else 0.0
    return SplineTile(tuple(points), duration, method, name)
