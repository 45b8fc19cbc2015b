"""Recordings are resampled whole once per step and their clips read from it, up to their ends."""

from __future__ import annotations

import numpy as np
import pytest

from timeline import edits
from timeline.bench.scenes import _tones
from timeline.model import Project
from timeline.rendering.mixer import Mixer
from timeline.signal import resample
from timeline.signal.render_presets import preset
from timeline.tiles import SampledTile

FULL = 0.18  # drive full scale, N*m
T48 = np.arange(96_000) / 48_000.0


def _trimmed(start: float, source_in: float, source_out: float, stretch: float = 1.0,
             reverse: bool = False) -> Project:  # fmt: skip
    p = edits.new_project(templates=False)
    p, track = edits.add_track(p, "drive")
    p, tile = edits.add_tile(p, SampledTile(_tones(T48), 48_000.0, "take"))
    p, clip = edits.add_clip(p, track, tile, start, source_in=source_in, source_out=source_out)
    if stretch != 1.0:
        p = edits.stretch_clip(p, clip, stretch)
    return edits.set_clip(p, clip, reverse=reverse) if reverse else p


@pytest.mark.parametrize(
    ("start", "source_in", "stretch", "reverse"),
    [(0.1, 0.2934, 1.0, False), (0.10003, 0.4, 1.37, False), (0.2, 0.21213, 1.0, True)],
)
def test_a_trimmed_clip_is_within_1e_5_of_its_tones_to_its_first_and_last_sample(
    start: float, source_in: float, stretch: float, reverse: bool
) -> None:
    # A segment resampled per clip started and ended the resampler's transient within 53 output
    # samples of the clip: 9e-5 to 2e-4 of full scale at its first or last sample.
    p = _trimmed(start, source_in, source_in + 0.36, stretch, reverse)
    clip = p.tracks[0].clips[0]
    out = Mixer().render(p, 0.0, 1.0)["drive"] / FULL
    t = np.arange(out.size) / 10_000.0
    inside = np.flatnonzero((t >= clip.start) & (t < clip.end))
    x = (t[inside] - clip.start) / stretch
    ref = _tones(clip.source_out - 1 / 48_000.0 - x if reverse else source_in + x)
    err = np.abs(out[inside] - ref)
    assert inside.size >= 3_600 and err.max() < 1e-5
    assert err[0] < 1e-5 and err[-1] < 1e-5


def test_the_kept_resampling_gives_the_bits_of_a_fresh_one() -> None:
    p = _trimmed(0.10003, 0.4, 1.3, 1.37)
    first = Mixer().render(p, 0.0, 1.5)["drive"].copy()
    assert len(resample._kept) >= 1
    resample.forget_resampled()
    assert len(resample._kept) == 0
    again = Mixer().render(p, 0.0, 1.5)["drive"]
    assert np.array_equal(first, again) and np.abs(first).max() > 0.1


def test_a_recording_its_owner_can_change_is_resampled_per_clip() -> None:
    data = _tones(T48)  # writable: never kept, since its values may change under the key
    before = len(resample._kept)
    values = resample.sample_grid(data, 48_000.0, 0.30001, 1e-4, 2_000, preset("normal"))
    assert len(resample._kept) == before
    np.testing.assert_allclose(values, _tones(0.30001 + 1e-4 * np.arange(2_000)), atol=3e-4)


def test_a_recording_made_from_an_array_keeps_its_own_samples_and_can_be_renamed() -> None:
    data = _tones(T48[:480])
    first = float(data[0])
    tile = SampledTile(data, 48_000.0, "take")
    data[0] = 5.0  # the caller's array, not the tile's
    renamed = tile.with_name("renamed")  # refused before: the tile's copy was a view
    assert renamed.name == "renamed" and renamed.data is tile.data and tile.data[0] == first
