"""Synthetic projects the benchmarks and stability tests render (deterministic, seeded)."""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from timeline import edits
from timeline.model import Clip, Fade, Project
from timeline.tiles import SampledTile, Tile, generator, spline


@dataclass(frozen=True)
class LargeSpec:
    """Size of the large mixing project."""

    tracks: int = 64
    clips: int = 20_000
    seconds: float = 600.0
    shapes: int = 200  # distinct clip shapes (tile, trim, stretch, fades); 0 = every clip its own
    off_grid: bool = False  # starts anywhere (as dragged without snapping), not on sample times


FULL = LargeSpec()
QUICK = LargeSpec(tracks=16, clips=2_000, seconds=60.0, shapes=50)


def _palette(rng: np.random.Generator) -> list[Tile]:
    """Generators, splines and imported-style 48 kHz recordings, as a designer's palette has."""
    tiles: list[Tile] = []
    for f in (40.0, 90.0, 175.0, 250.0):
        tiles.append(generator("sine", 2.0, frequency=f))
    tiles += [
        generator("chirp", 2.0, f0=20.0, f1=300.0),
        generator("am", 2.0, carrier=175.0, modulation=8.0),
        generator("noise", 2.0, seed=3.0),
        generator("adsr", 2.0),
        generator("square", 2.0, frequency=30.0),
        generator("detents", 2.0, count=12.0),
    ]
    for method in ("natural", "pchip"):
        for _ in range(3):
            t = np.sort(np.r_[0.0, rng.uniform(0.05, 1.95, 6), 2.0])
            tiles.append(spline(list(zip(t, rng.uniform(-1, 1, t.size), strict=True)), 2.0, method))
    for seconds in (0.5, 1.0, 2.0):
        n = int(seconds * 48_000)
        x = np.cumsum(rng.standard_normal(n))
        x = np.sin(2 * np.pi * 120.0 * np.arange(n) / 48_000) * 0.6 + 0.4 * x / np.abs(x).max()
        tiles.append(SampledTile(x, 48_000.0, "recording"))
    return tiles


def _shape(rng: np.random.Generator, tile_id: str, tile: Tile) -> Clip:
    """A clip shape: a trimmed, maybe stretched, reversed or faded use of a tile."""
    length = float(rng.uniform(0.2, 1.0) * tile.duration)
    source_in = float(rng.uniform(0.0, tile.duration - length))
    stretch = float(rng.choice([1.0, 1.0, 1.0, 0.5, 1.5, 2.0]))
    duration = length * stretch
    fade_in = (
        Fade(float(rng.uniform(0, 0.3) * duration), "equal-power") if rng.random() < 0.4 else Fade()
    )
    fade_out = Fade(float(rng.uniform(0, 0.3) * duration)) if rng.random() < 0.4 else Fade()
    return Clip(
        "shape", tile_id, 0.0, source_in, source_in + length, stretch=stretch,
        reverse=bool(rng.random() < 0.1), fade_in=fade_in, fade_out=fade_out,
    )  # fmt: skip


def large_project(spec: LargeSpec = FULL, seed: int = 0) -> Project:
    """Tracks of drive, stiffness and damping filled with clips at grid-aligned starts.

    Clips are placements of `spec.shapes` distinct shapes with their own gains (a design built by
    duplicating and pasting), or all distinct when shapes is 0.
    """
    rng = np.random.default_rng(seed)
    project = edits.new_project(templates=False)
    tile_ids = []
    for tile in _palette(rng):
        project, tile_id = edits.add_tile(project, tile)
        tile_ids.append(tile_id)
    count = spec.shapes or spec.clips
    shapes = []
    for _ in range(count):
        i = int(rng.integers(len(tile_ids)))
        shapes.append(_shape(rng, tile_ids[i], project.tile(tile_ids[i])))
    kinds = ("drive", "drive", "drive", "stiffness", "damping")
    per_track = spec.clips // spec.tracks
    rate = project.rate
    tracks = []
    serial = 0
    for t in range(spec.tracks):
        project, track_id = edits.add_track(project, kinds[t % len(kinds)])
        chosen = (
            rng.integers(count, size=per_track)
            if spec.shapes
            else range(serial, serial + per_track)
        )
        starts = np.sort(rng.uniform(0.0, spec.seconds - 6.0, per_track))
        clips = []
        for j, start in zip(chosen, starts, strict=True):
            if not spec.off_grid:
                start = round(float(start) * rate) / rate  # snapped to the grid, as the editor does
            clips.append(
                replace(
                    shapes[int(j)], id=f"c{serial}", start=start, gain=float(rng.uniform(0.1, 1))
                )
            )
            serial += 1
        tracks.append(replace(project.track(track_id), clips=tuple(clips)))
    return replace(project, tracks=tuple(tracks))


def clip_samples(project: Project, rate: float) -> int:
    """Total output samples covered by clips (what a mixer must at least add once)."""
    return sum(
        int(np.ceil(c.end * rate - 1e-9)) - int(np.ceil(c.start * rate - 1e-9))
        for t in project.tracks
        for c in t.clips
    )


@dataclass(frozen=True)
class Scene:
    """A one-clip project and its exact values (tile units) on the render grid."""

    name: str
    project: Project
    reference: np.ndarray  # float64 values of the clip's shape at t = i / rate
    resampled: bool  # the scene goes through a resampler (stop-band rejection applies)


SCENE_RATE = 10_000.0
RECORDING_RATE = 48_000.0
_TONES = ((37.0, 0.5, 0.3), (175.0, 0.3, 1.1), (410.0, 0.15, 2.0), (3_300.0, 0.05, 0.7))


def _tones(t: np.ndarray, stretch: float = 1.0) -> np.ndarray:
    """A recording's in-band content: tones below 0.7 x the 10 kHz grid's Nyquist."""
    waves = (a * np.sin(2 * np.pi * f / stretch * t + ph) for f, a, ph in _TONES)
    return sum(waves, np.zeros(t.shape))


def _one_clip(tile: Tile, seconds: float, **fields: Any) -> Project:
    """One clip of the tile; fields: stretch=factor, in=/out=(fade length, shape)."""
    project = edits.new_project(templates=False)
    project, track = edits.add_track(project, "drive")
    project, tile_id = edits.add_tile(project, tile)
    project, clip = edits.add_clip(project, track, tile_id, 0.0)
    for name, value in fields.items():
        if name == "stretch":
            project = edits.stretch_clip(project, clip, float(value))
        else:
            project = edits.set_fade(project, clip, name, *value)
    return project


def quality_scenes(seconds: float = 2.0) -> list[Scene]:
    """Sine, chirp, spline, a 48 kHz recording, a stretched recording and a faded clip."""
    t = np.arange(int(seconds * SCENE_RATE)) / SCENE_RATE
    scenes = []
    sine = generator("sine", seconds, frequency=175.0)
    scenes.append(Scene("sine 175 Hz", _one_clip(sine, seconds), sine.evaluate(t), False))
    chirp = generator("chirp", seconds, f0=20.0, f1=400.0)
    scenes.append(Scene("chirp 20-400 Hz", _one_clip(chirp, seconds), chirp.evaluate(t), False))
    rng = np.random.default_rng(7)
    knots = np.linspace(0.0, seconds, 12)
    curve = spline(list(zip(knots, rng.uniform(-1, 1, knots.size), strict=True)), seconds)
    scenes.append(Scene("spline, 12 points", _one_clip(curve, seconds), curve.evaluate(t), False))
    n48 = int(seconds * RECORDING_RATE)
    t48 = np.arange(n48) / RECORDING_RATE
    noise = 0.05 * np.sin(2 * np.pi * 7_300.0 * t48)  # above the 5 kHz Nyquist: must vanish
    recording = SampledTile(_tones(t48) + noise, RECORDING_RATE, "recording")
    inside = t <= (n48 - 1) / RECORDING_RATE
    scenes.append(
        Scene("48 kHz recording", _one_clip(recording, seconds), _tones(t) * inside, True)
    )
    stretched = _one_clip(recording, seconds / 1.37, stretch=1.37)
    short = t[t < seconds / 1.37 * 1.37 - 1.37 / RECORDING_RATE]
    ref = np.zeros_like(t)
    ref[: short.size] = _tones(short, 1.37)
    scenes.append(Scene("recording stretched x1.37", stretched, ref, True))
    faded = _one_clip(sine, seconds, **{"in": (0.5, "exponential"), "out": (0.7, "s-curve")})
    from timeline.signal.fades import fade_in_gain

    env = fade_in_gain(t / 0.5, "exponential") * fade_in_gain((seconds - t) / 0.7, "s-curve")
    scenes.append(Scene("sine with fades", faded, sine.evaluate(t) * env, False))
    return scenes
