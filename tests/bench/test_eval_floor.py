"""The evaluation floor batches each tile's samples and gives the values the mixer renders."""

from __future__ import annotations

import numpy as np

from timeline import edits
from timeline.bench.eval_floor import evaluation_work
from timeline.model import Project
from timeline.rendering.clip_render import clip_sample_range, render_shape
from timeline.signal.render_presets import preset
from timeline.tiles import SampledTile, Tile, generator


def _project(tile: Tile, starts: list[float], stretch: float = 1.0) -> Project:
    project = edits.new_project(templates=False)
    project, track = edits.add_track(project, "drive")
    project, tile_id = edits.add_tile(project, tile)
    for start in starts:
        project, clip = edits.add_clip(project, track, tile_id, start)
        if stretch != 1.0:
            project = edits.stretch_clip(project, clip, stretch)
    return project


def test_a_generator_clip_is_evaluated_to_the_mixers_values() -> None:
    project = _project(generator("square", 1.0, frequency=30.0), [0.12345], stretch=1.5)
    (work,) = evaluation_work(project, 0.0, 2.0)
    clip = project.tracks[0].clips[0]
    i0, i1 = clip_sample_range(clip, 0.0, project.rate, 20_000)
    tile = project.tile(clip.tile_id)
    mixed = render_shape(clip, tile, i0 / project.rate - clip.start, project.rate, i1 - i0,
                         preset("normal"))  # fmt: skip
    values = work.run()
    assert values.shape == mixed.shape == (15_000,)
    assert np.abs(mixed).max() > 0.9  # the band-limited square, not zeros
    np.testing.assert_allclose(values, mixed, rtol=0, atol=1e-9)


def test_clips_of_one_tile_at_one_spacing_are_one_evaluation() -> None:
    sine = generator("sine", 0.5, frequency=175.0)
    (work,) = evaluation_work(_project(sine, [0.0, 0.70001, 1.4]), 0.0, 2.0)
    assert work.run().size == 3 * 5_000
    stretched = _project(sine, [0.0, 0.70001], stretch=2.0)
    assert len(evaluation_work(stretched, 0.0, 2.0)) == 1  # both clips stretched alike
    mixed = edits.stretch_clip(stretched, stretched.tracks[0].clips[0].id, 0.5)
    assert [w.run().size for w in evaluation_work(mixed, 0.0, 2.0)] == [5_000, 10_000]


def test_recordings_are_resampled_once_and_delayed_per_sample() -> None:
    t = np.arange(24_000) / 48_000.0
    recording = SampledTile(np.sin(2 * np.pi * 120.0 * t), 48_000.0, "take")
    works = evaluation_work(_project(recording, [0.01234, 0.3]), 0.0, 1.0)
    assert [w.label for w in works] == ["take resampled", "take delayed"]
    resampled, delayed = (w.run() for w in works)
    assert resampled.size == round((24_000 + 2 * 256) / 4.8)  # the recording and its padding
    assert delayed.size == 5_000  # only the off-grid clip needs the fractional delay
    on_rate = SampledTile(recording.data, 10_000.0, "take")
    assert evaluation_work(_project(on_rate, [0.5]), 0.0, 4.0) == []  # copied, not evaluated


def test_fades_are_evaluated_over_their_spans_only() -> None:
    project = _project(generator("sine", 1.0, frequency=40.0), [0.25])
    clip = project.tracks[0].clips[0]
    project = edits.set_fade(project, clip.id, "in", 0.1, "equal-power")
    works = evaluation_work(project, 0.0, 2.0)
    assert [w.label for w in works] == ["sine", "equal-power fades"]
    gains = works[1].run()
    assert gains.size == 1_001  # 0.1 s at 10 kHz, ending at the sample where the gain is 1
    assert gains[0] == 0.0 and gains[-1] == 1.0 and np.all(np.diff(gains) > 0)
