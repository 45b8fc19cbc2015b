"""After one edit only the touched clip and blocks are recomputed."""

import numpy as np

from timeline import Mixer, edits
from timeline.tiles import generator


def many_clips(n=50):
    p = edits.new_project(templates=False)
    p, track = edits.add_track(p, "drive")
    p, tile = edits.add_tile(p, generator("sine", 1.0, frequency=7))
    ids = []
    for i in range(n):
        p, c = edits.add_clip(p, track, tile, float(i))
        ids.append(c)
    return p, ids


def test_one_edit_rerenders_one_clip_and_only_its_blocks():
    p, ids = many_clips()
    mixer = Mixer()
    full = mixer.render(p)["drive"]
    assert mixer.stats.clip_renders == 50
    before = mixer.stats.block_sums
    p2 = edits.set_clip_gain(p, ids[10], 0.5)
    again = mixer.render(p2)["drive"]
    assert mixer.stats.clip_renders == 51  # only the edited clip
    assert mixer.stats.block_sums - before <= 3  # 1 s at 10 kHz spans at most 3 blocks of 8192
    np.testing.assert_array_equal(again[:100_000], full[:100_000])
    np.testing.assert_allclose(again[100_000:110_000], 0.5 * full[100_000:110_000])
    np.testing.assert_array_equal(again[110_000:], full[110_000:])
    assert np.array_equal(Mixer().render(p2)["drive"], again)
