"""Rendering a short window visits only nearby clips, with the same numbers as visiting all."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from timeline.bench.scenes import LargeSpec, large_project
from timeline.model import Clip, Track
from timeline.rendering.mixer import Mixer


def test_windows_render_bit_identical_to_walking_every_clip(monkeypatch):
    project = large_project(LargeSpec(8, 240, 20.0, 0, off_grid=True))
    windows = [(t, t + w) for t in np.arange(0.0, 20.0, 1.37) for w in (0.01, 0.5, 3.0)]
    fast = Mixer()
    got = [fast.render(project, a, b) for a, b in windows]
    monkeypatch.setattr(Track, "clips_between", lambda self, t0, t1, margin: self.clips)
    walk = Mixer()
    for (a, b), layers in zip(windows, got, strict=True):
        want = walk.render(project, a, b)
        assert layers.keys() == want.keys()
        for kind in want:
            assert np.array_equal(layers[kind], want[kind]), (a, b, kind)


@settings(max_examples=200, deadline=None)
@given(
    st.lists(st.tuples(st.floats(-5, 50), st.floats(0.001, 8)), max_size=30),
    st.floats(-10, 60),
    st.floats(0, 10),
    st.booleans(),
)
def test_every_clip_touching_the_window_is_among_those_visited(spans, t0, width, shuffled):
    clips = [Clip(f"c{i}", "t", s, 0.0, d) for i, (s, d) in enumerate(spans)]
    if not shuffled:
        clips.sort(key=lambda c: (c.start, c.id))
    track = Track("t1", "drive", "Drive", tuple(clips))
    visited = {c.id for c in track.clips_between(t0, t0 + width, 1e-4)}
    touching = {c.id for c in clips if c.end > t0 and c.start < t0 + width}
    assert touching <= visited
    ordered = [c.id for c in track.clips if c.id in visited]
    assert [c.id for c in track.clips_between(t0, t0 + width, 1e-4)] == ordered
