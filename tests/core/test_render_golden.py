"""A render of every tile kind at its parameter extremes keeps the bits the code gave before the
render kernels were fused (issue 19): the SHA-256 of each layer, numpy forms and compiled loops
alike, against tests/golden/render_bits.json (written by tests/golden/make/render_bits.py with
the commit named there)."""

from __future__ import annotations

import hashlib
import json
from dataclasses import replace
from pathlib import Path
from unittest import mock

import numpy as np
import pytest

from timeline import edits
from timeline.model import Clip, Fade, Project
from timeline.rendering.mixer import Mixer
from timeline.signal import compiled
from timeline.signal.vibration_design import Emphasis, VibrationDesign
from timeline.tiles import SampledTile, VibrationTile, generator, spline

GOLDEN = Path(__file__).resolve().parents[1] / "golden" / "render_bits.json"
SECONDS = 3.0
FADES = ("linear", "equal-power", "exponential", "s-curve")


def _tiles() -> list:
    """Every tile kind, some at their parameter extremes."""
    rng = np.random.default_rng(7)
    walk = np.cumsum(rng.standard_normal(2_400)) * 0.05
    return [
        generator("sine", 1.0, frequency=37.0, phase=0.3),
        generator("square", 1.0, frequency=30.0),
        generator("square", 1.0, frequency=13.0, duty=0.2),
        generator("triangle", 1.0, frequency=55.0),
        generator("saw", 1.0, frequency=21.0, amplitude=5e-324),
        generator("chirp", 1.0, f0=20.0, f1=300.0),
        generator("chirp", 1.0, f0=5.0, f1=6_000.0, exponential=1.0),
        generator("ramp", 1.0, start=-1.0, end=2.0),
        generator("constant", 1.0, value=-0.7),
        generator("noise", 1.0, seed=3.0),
        generator("noise", 1.0, seed=-(2.0**63), bandwidth=40_000.0),  # white, above Nyquist
        generator("detents", 1.0, count=12.0),
        generator("wall", 1.0, edge=0.3, width=0.2),
        generator("stribeck", 1.0),
        generator("adsr", 1.0),
        generator("am", 1.0, carrier=175.0, modulation=8.0, depth=-3.0),
        generator("am", 1.0, carrier=4_999.0, modulation=2.0),  # masked per sample
        generator("emphasis", 1.0, frequency=1.0),
        spline([(0.0, 0.0), (0.2, 1.0), (0.5, -0.5), (0.9, 0.3), (1.0, 0.0)], 1.0, "natural"),
        spline([(0.1, 0.0), (0.4, 1.0), (0.7, -0.5), (0.8, 0.3)], 1.0, "pchip"),
        spline([(0.5, 0.25)], 1.0),
        spline([(0.0, -1.0), (1.0, 1.0)], 1.0),
        SampledTile(walk, 1_000.0, "on the grid"),
        SampledTile(walk, 48_000.0, "resampled"),
        SampledTile(walk.astype(np.float32).astype(np.float64), 7_919.3, "odd rate"),
        VibrationTile(VibrationDesign(((0.0, 0.2), (0.4, 1.0), (0.9, 0.1)),
                                      ((0.0, 0.1), (0.9, 0.8)), (Emphasis(0.5, 0.9, 0.4),), 0.9)),
    ]  # fmt: skip


def _extremes() -> list:
    """Tiles at the ends of the float range, on a layer of their own (they would swamp the rest)."""
    return [
        generator("sine", 1.0, frequency=4_990.0, amplitude=1e290),  # at Nyquist, huge
        generator("am", 1.0, carrier=90.0, amplitude=1e290),
        generator("noise", 1.0, seed=2.0**64, amplitude=-1e290),
        spline([(0.1, 0.0), (0.4, 1e290), (0.7, -0.5), (0.8, 0.3)], 1.0, "pchip"),
        spline([(0.1, 5e-324), (0.4, -1e-310), (0.9, 3e-320)], 1.0, "natural"),
        SampledTile(np.array([1e30, -1e30, 5e-324] * 40), 3_000.0, "extreme samples"),
    ]


def golden_project() -> Project:
    """Three tracks of clips of every tile kind: trimmed, stretched, reversed, repeated, faded
    with every fade shape, on and off the sample grid; a fourth of the extremes."""
    project = edits.new_project(templates=False)
    ids: dict[str, list[str]] = {"plain": [], "extreme": []}
    for group, tiles in (("plain", _tiles()), ("extreme", _extremes())):
        for tile in tiles:
            project, tile_id = edits.add_tile(project, tile)
            ids[group].append(tile_id)
    tracks = []
    for t, kind in enumerate(("drive", "stiffness", "damping", "mass")):
        project, track_id = edits.add_track(project, kind)
        clips = []
        for i, tile_id in enumerate(ids["extreme" if kind == "mass" else "plain"]):
            duration = project.tile(tile_id).duration
            j = i + 5 * t
            a = 0.1 * duration * (j % 3)
            b = duration * (1.0 - 0.07 * (j % 4))
            start = 0.05 * ((7 * j) % 40) + (0.0 if j % 2 else 1.37e-5 * (j + 1))
            fade = Fade(0.3 * (b - a), FADES[j % 4]) if j % 3 else Fade()
            clips.append(Clip(
                f"c{t}-{i}", tile_id, start, a, b, stretch=(1.0, 0.5, 1.7, 3.0)[j % 4],
                stretch_mode="repeat" if j % 7 == 3 else "squeeze", loop_phase=0.01 * (j % 5),
                gain=0.3 + 0.1 * (j % 5), scale=(1.0, -2.0)[j % 2], offset=0.1 * (j % 3),
                reverse=j % 5 == 1, fade_in=fade, fade_out=Fade(0.2 * (b - a), FADES[(j + 1) % 4]),
            ))  # fmt: skip
        tracks.append(replace(project.track(track_id), clips=tuple(clips)))
    return replace(project, tracks=tuple(tracks))


def render_digests(loops: bool) -> dict[str, str]:
    """SHA-256 of each layer's float64 bytes, with the compiled loops or with numpy alone."""
    project = golden_project()
    if loops:
        import timeline.signal.render_kernels  # noqa: F401  (loaded: the loops are taken)
        import timeline.signal.shape_kernels  # noqa: F401

        layers = Mixer().render(project, 0.0, SECONDS)
    else:
        with mock.patch.object(compiled, "compiled_wanted", lambda n: False):
            layers = Mixer().render(project, 0.0, SECONDS)
    return {
        name: hashlib.sha256(np.ascontiguousarray(v, dtype=np.float64).tobytes()).hexdigest()
        for name, v in sorted(layers.items())
    }


@pytest.mark.parametrize("loops", [False, True], ids=["numpy", "compiled"])
def test_every_tile_kind_renders_the_bits_it_rendered_before_the_kernels_were_fused(loops):
    golden = json.loads(GOLDEN.read_text())
    assert render_digests(loops) == golden["layers"]
