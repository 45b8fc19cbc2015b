"""Re-renders after edits equal fresh renders bit for bit, and never change a result already held.

tests/core/test_mixer_cache.py checks one gain edit; here random sequences of moves, gains,
removals, mutes, track gains, moves between tracks and tile replacements, at each preset.
"""

from __future__ import annotations

import random
from dataclasses import replace
from types import MappingProxyType

import numpy as np
import pytest

from timeline import Mixer, edits
from timeline.bench.scenes import LargeSpec, large_project
from timeline.model import Project
from timeline.signal.render_presets import PRESETS
from timeline.tiles import generator

SECONDS = 30.0


def edit(project: Project, rng: random.Random, step: int) -> Project:
    track = rng.choice([t for t in project.tracks if t.clips])
    clip = rng.choice(track.clips)
    kind = step % 7
    if kind == 0:
        return edits.move_clip(project, clip.id, max(0.0, clip.start + rng.uniform(-1, 1)))
    if kind == 1:
        return edits.set_clip_gain(project, clip.id, rng.uniform(0, 2))
    if kind == 2:
        return edits.remove_clip(project, clip.id)
    if kind == 3:
        return edits.set_track(project, track.id, mute=not track.mute)
    if kind == 4:
        return edits.set_track(project, track.id, gain=rng.uniform(0.1, 2))
    if kind == 5:
        return edits.move_clip(project, clip.id, track_id=rng.choice(project.tracks).id)
    tile = project.tile(clip.tile_id)  # same tile id, new content
    new = generator("sine", tile.duration, frequency=rng.uniform(20, 300))
    return replace(project, tiles=MappingProxyType({**project.tiles, clip.tile_id: new}))


@pytest.mark.parametrize("quality", list(PRESETS))
def test_edit_sequences_match_fresh_renders_and_keep_held_results(quality: str) -> None:
    project = large_project(LargeSpec(tracks=6, clips=240, seconds=SECONDS, shapes=30), seed=3)
    mixer = Mixer()
    mixer.render(project, 0.0, SECONDS, quality=quality)
    rng = random.Random(1)
    held = []
    for step in range(21):
        project = edit(project, rng, step)
        out = mixer.render(project, 0.0, SECONDS, quality=quality)
        fresh = Mixer().render(project, 0.0, SECONDS, quality=quality)
        assert out.keys() == fresh.keys()
        for kind, values in fresh.items():
            assert values.dtype == out[kind].dtype
            np.testing.assert_array_equal(out[kind], values)
        if step % 3 == 0:
            held.append((out, {kind: values.copy() for kind, values in fresh.items()}))
    for out, expected in held:
        for kind, values in expected.items():
            np.testing.assert_array_equal(out[kind], values)
    assert mixer.stats.block_hits > 0


def test_results_are_read_only() -> None:
    project = large_project(LargeSpec(tracks=2, clips=20, seconds=SECONDS, shapes=5))
    for values in Mixer().render(project, 0.0, SECONDS).values():
        with pytest.raises(ValueError, match="read-only"):
            values[0] = 1.0
