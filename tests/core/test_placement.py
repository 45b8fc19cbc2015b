"""Finding a free spot on a track, and the spans where clips overlap."""

from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st

from timeline import edits
from timeline.edits.placement import free_start, overlaps
from timeline.tiles import generator


def track_with(spans):
    p = edits.new_project(templates=False)
    p, tile = edits.add_tile(p, generator("sine", 1.0, frequency=5))
    p, track = edits.add_track(p, "drive")
    ids = []
    for a, b in spans:
        p, c = edits.add_clip(p, track, tile, a, source_out=b - a)
        ids.append(c)
    return p, track, ids


def test_free_start_takes_the_first_gap_that_fits():
    p, track, ids = track_with([(0.0, 1.0), (1.2, 1.5), (2.0, 2.5)])
    assert free_start(p, track, 0.2, 0.0) == pytest.approx(1.0)
    assert free_start(p, track, 0.4, 0.0) == pytest.approx(1.5)
    assert free_start(p, track, 0.6, 0.0) == pytest.approx(2.5)
    assert free_start(p, track, 0.6, 0.0, limit=2.0) is None
    assert free_start(p, track, 0.4, 0.0, ignore=[ids[1]]) == pytest.approx(1.0)
    assert free_start(p, track, 1.0, -3.0) == pytest.approx(2.5)


def test_overlaps_names_both_clips_and_the_shared_span():
    p, track, (a, b, c) = track_with([(0.0, 1.0), (0.75, 1.5), (2.0, 2.5)])
    found = overlaps(p, track)
    assert found == {a: ((0.75, 1.0),), b: ((0.75, 1.0),)}


@given(
    st.lists(st.tuples(st.floats(0, 5), st.floats(0.01, 1)), max_size=6),
    st.floats(0.01, 2),
    st.floats(0, 6),
)
def test_the_free_start_never_covers_a_clip(spans, length, at):
    p, track, _ = track_with([(a, a + d) for a, d in spans])
    start = free_start(p, track, length, at)
    assert start >= at
    for clip in p.track(track).clips:
        assert clip.end <= start + 1e-9 or clip.start >= start + length - 1e-9


def _overlaps_by_loop(clips, eps):
    """The clip-by-clip walk the vectorised `overlaps` replaced (a second method)."""
    clips = sorted(clips, key=lambda c: (c.start, c.end))
    n = len(clips)
    later = [float("-inf")] * (n + 1)
    for i in range(n - 1, -1, -1):
        later[i] = max(later[i + 1], clips[i].end)
    found, reach = {}, float("-inf")
    for i, c in enumerate(clips):
        lo, hi = float("inf"), float("-inf")
        if reach > c.start + eps:
            lo, hi = c.start, min(c.end, reach)
        if i + 1 < n and clips[i + 1].start < c.end - eps:
            lo = min(lo, clips[i + 1].start)
            hi = max(hi, min(c.end, later[i + 1]))
        if hi - lo > eps:
            found[c.id] = ((lo, hi),)
        reach = max(reach, c.end)
    return found


SPAN_STARTS = st.sampled_from([0.0, 0.5, 1.0, 1.25]) | st.floats(0, 5)
SPAN_LENGTHS = st.sampled_from([0.25, 0.5]) | st.floats(0.01, 1)  # ties and touching ends too


@given(st.lists(st.tuples(SPAN_STARTS, SPAN_LENGTHS), max_size=12))
def test_overlaps_equal_the_clip_by_clip_walk(spans):
    from timeline.edits.placement import EPS

    p, track, _ = track_with([(a, a + d) for a, d in spans])
    assert overlaps(p, track) == _overlaps_by_loop(p.track(track).clips, EPS)
