"""Clip edges are exact at any time and rate: render, chunks, export and play agree to the bit.

The reference for which samples a clip covers is exact rational arithmetic (fractions.Fraction):
sample k (at k/rate) belongs to a clip when start <= k/rate < start + duration, where start and
duration are the values the clip was meant to have (k/rate for a clip placed on the grid, the
float's own exact value for one placed off it).
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest

from timeline import edits
from timeline.files.exporting import project_layers
from timeline.model import Project
from timeline.rendering.mixer import Mixer
from timeline.rendering.playback import coefficient_blocks
from timeline.tiles import SampledTile, generator

RATES = [10_000.0, 192_000.0]
TIMES = [0.5, 100.0, 1000.0, 1200.0, 3599.0]  # seconds: up to an hour
LENGTHS = [1, 7, 333]  # samples


def covered(start: Fraction, duration: Fraction, rate: float) -> range:
    """The samples k with start <= k/rate < start + duration, in exact arithmetic."""
    r = Fraction(rate)
    return range(math.ceil(start * r), math.ceil((start + duration) * r))


def ramp(length: int, rate: float) -> SampledTile:
    """A tile of `length` samples at `rate`, each a distinct non-zero value."""
    return SampledTile(1.0 + np.arange(length) / length, rate)


def placed(rate: float, items: list[tuple[float, SampledTile]]) -> Project:
    """A project at `rate` with one drive track holding the tiles at the given starts."""
    project = edits.new_project(rate=rate, templates=False)
    project, track = edits.add_track(project, "drive")
    for start, tile in items:
        project, tile_id = edits.add_tile(project, tile)
        project, _ = edits.add_clip(project, track, tile_id, start)
    return project


def grid_clips(rate: float, seconds: float) -> list[tuple[int, int]]:
    """(first sample, length) of clips on the grid near `seconds`, a few samples apart."""
    k = round(seconds * rate)
    return [(k + 3 + 401 * i + 17 * i * i, length) for i, length in enumerate(LENGTHS)]


def drive(layers: dict[str, np.ndarray]) -> np.ndarray:
    return layers["drive"]


@pytest.mark.parametrize("rate", RATES)
@pytest.mark.parametrize("seconds", TIMES)
def test_clips_on_the_grid_cover_exactly_their_samples(rate: float, seconds: float) -> None:
    clips = grid_clips(rate, seconds)
    project = placed(rate, [(k / rate, ramp(length, rate)) for k, length in clips])
    lo, hi = clips[0][0] - 50, clips[-1][0] + clips[-1][1] + 50
    out = drive(Mixer().render(project, lo / rate, hi / rate, rate))
    want = np.zeros(hi - lo)
    full = project.tracks[0].clips[0].gain * 0.18  # a drive track's full scale, gain 1
    for k, length in clips:
        samples = covered(Fraction(k) / Fraction(rate), Fraction(length) / Fraction(rate), rate)
        assert (samples.start, samples.stop) == (k, k + length)
        want[k - lo : k + length - lo] = full * (1.0 + np.arange(length) / length)
    assert np.array_equal(out, want)


@pytest.mark.parametrize("rate", RATES)
@pytest.mark.parametrize("seconds", [1.0, 3599.0])
def test_clips_off_the_grid_cover_the_samples_after_their_exact_start(
    rate: float, seconds: float
) -> None:
    rng = np.random.default_rng(7)
    starts = [seconds + (round(rng.uniform(0, 1000)) + f) / rate for f in (0.001, 0.25, 0.5, 0.999)]
    tile = ramp(20, rate)
    project = placed(rate, [(s, tile) for s in starts])
    lo = round(seconds * rate)
    out = drive(Mixer().render(project, lo / rate, (lo + 1100) / rate, rate))
    got = set((np.flatnonzero(out) + lo).tolist())
    want: set[int] = set()
    for s in starts:
        want.update(covered(Fraction(s), Fraction(tile.duration), rate))
    assert got == want


def chunked(mixer: Mixer, project: Project, lo: int, hi: int, rate: float, size: int) -> np.ndarray:
    """The samples [lo, hi) rendered in chunks of `size` samples, joined."""
    pieces = mixer.render_chunks(project, lo / rate, hi / rate, rate, chunk=size / rate)
    return np.concatenate([drive(layers) for _, layers in pieces])


def mixed_project(rate: float, seconds: float) -> tuple[Project, int, int]:
    """Grid clips of sampled tiles, an off-grid one and a 0.7 s sine crossing many chunks."""
    clips = grid_clips(rate, seconds)
    items = [(k / rate, ramp(length, rate)) for k, length in clips]
    items.append(((clips[0][0] + 2.5) / rate, ramp(50, rate)))
    project = placed(rate, items)
    project, tile_id = edits.add_tile(project, generator("sine", 0.7, frequency=31.0))
    sine_at = clips[0][0] + 11
    project, _ = edits.add_clip(project, project.tracks[0].id, tile_id, sine_at / rate)
    return project, clips[0][0] - 40, sine_at + round(0.7 * rate) + 40


@pytest.mark.parametrize("rate", RATES)
@pytest.mark.parametrize("seconds", [2.0, 1000.0, 3599.0])
def test_whole_and_chunked_renders_agree_to_the_bit(rate: float, seconds: float) -> None:
    project, lo, hi = mixed_project(rate, seconds)
    whole = drive(Mixer().render(project, lo / rate, hi / rate, rate))
    assert np.count_nonzero(whole) > 0.9 * (hi - lo)
    for size in (997, 4096, 10_007, 65_536 + 3):
        assert np.array_equal(chunked(Mixer(), project, lo, hi, rate, size), whole), size
    earlier = drive(Mixer().render(project, (lo - 12_345) / rate, hi / rate, rate))
    assert np.array_equal(earlier[12_345:], whole)


@pytest.mark.parametrize(("rate", "seconds"), [(10_000.0, 150.0), (192_000.0, 15.0)])
def test_render_export_and_play_agree_to_the_bit(rate: float, seconds: float) -> None:
    project, lo, hi = mixed_project(rate, seconds)
    n = round(project.duration * rate)
    whole = drive(Mixer().render(project, 0.0, project.duration, rate))
    exported = project_layers(project, rate).columns["drive"]
    blocks, _ = coefficient_blocks(project, rate)
    played = np.concatenate([block.d for block in blocks])
    assert len(whole) == len(exported) == len(played) == n
    assert np.array_equal(exported, whole)
    assert np.array_equal(played, whole)
    window = drive(Mixer().render(project, lo / rate, hi / rate, rate))
    assert np.array_equal(whole[lo:], window[: n - lo])  # the project ends with the sine
    assert not whole[:lo].any() and not window[n - lo :].any()
