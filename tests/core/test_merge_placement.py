"""merge_clips places clips exactly on the sample grid at any time and rate (issue 20, item 2)."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

from timeline import edits
from timeline.rendering.mixer import Mixer
from timeline.tiles import SampledTile

SHAPE = [1.0, 2.0, 4.0]


@pytest.mark.parametrize("rate", [10_000.0, 192_000.0])
def test_merged_clips_at_an_hour_keep_every_sample(rate: float) -> None:
    """Clips at 3600 s + j/rate (j = 0, 4, ..., 156): each starts on its own grid sample.

    The reference index of each start is its float's exact value (Fraction) less 3600 s, times
    the rate, which is within 1e-6 of the whole j: the merged tile holds SHAPE at each index.
    A fixed 1e-9-sample tolerance moved about half of these one sample late at 192 kHz.
    """
    t0 = 3600.0
    project = edits.new_project(rate=rate, templates=False)
    project, track = edits.add_track(project, "drive")
    project, tile = edits.add_tile(project, SampledTile(np.array(SHAPE), rate))
    ids, starts = [], [t0 + j / rate for j in range(0, 160, 4)]
    for start in starts:
        project, clip = edits.add_clip(project, track, tile, start)
        ids.append(clip)
    expected = np.zeros(160 - 4 + len(SHAPE))
    for start in starts:
        exact = (Fraction(start) - Fraction(t0)) * Fraction(rate)
        k = round(exact)
        assert abs(exact - k) < Fraction(1, 10**6)  # the float start is on the grid
        expected[k : k + len(SHAPE)] += SHAPE
    before = Mixer().render(project, t0, t0 + 200 / rate)["drive"]
    merged, new_tile = edits.merge_clips(project, ids)
    assert merged.tile(new_tile).data.tolist() == expected.tolist()
    assert [c.start for c in merged.track(track).clips] == [t0]
    after = Mixer().render(merged, t0, t0 + 200 / rate)["drive"]
    assert after.tolist() == before.tolist()
