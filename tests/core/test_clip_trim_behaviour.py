"""Trims and splits of repeating and faded clips: the fields they leave, from hand arithmetic."""

import pytest

from timeline import edits
from timeline.model import Fade
from timeline.tiles import GeneratorTile


def _looped(times: float = 3.0):
    """A 0.1 s sine clip at 1 s looped `times` over (repeat mode), with its project."""
    p = edits.new_project(templates=False)
    p, track = edits.add_track(p, "drive")
    p, tile = edits.add_tile(p, GeneratorTile("sine", 0.1, (("frequency", 30.0),)))
    p, clip = edits.add_clip(p, track, tile, 1.0)
    return edits.stretch_clip(p, clip, times, "repeat"), clip


def test_trimming_a_loop_s_left_edge_moves_its_phase_by_the_cut():
    p, clip = _looped()
    c = edits.trim_clip(p, clip, 1.25).find_clip(clip)[1]
    # 0.25 s cut off a 0.1 s loop: it now starts 0.05 s into the loop and lasts 0.05 s
    assert (c.start, c.loop_phase) == (1.25, pytest.approx(0.05))
    assert (c.stretch, c.source_in, c.source_out) == (pytest.approx(0.5), 0.0, 0.1)


def test_extending_a_loop_to_the_left_keeps_its_phase_in_the_loop():
    p, clip = _looped()
    c = edits.trim_clip(p, clip, 0.95).find_clip(clip)[1]
    # 0.05 s earlier: the loop is entered 0.05 s in, not at -0.05 s
    assert c.loop_phase == pytest.approx(0.05) and c.duration == pytest.approx(0.35)
    c = edits.trim_clip(p, clip, 0.73).find_clip(clip)[1]  # 0.27 s earlier: 0.03 s in
    assert c.loop_phase == pytest.approx(0.03) and c.stretch == pytest.approx(5.7)


def test_trimming_a_loop_shortens_fades_longer_than_what_is_left():
    p, clip = _looped()
    p = edits.set_fade(edits.set_fade(p, clip, "in", 0.2), clip, "out", 0.15)
    c = edits.trim_clip(p, clip, 1.0, 1.1).find_clip(clip)[1]
    assert (c.fade_in.length, c.fade_out.length) == (pytest.approx(0.1), pytest.approx(0.1))
    kept = edits.trim_clip(p, clip, 1.0, 1.25).find_clip(clip)[1]
    assert (kept.fade_in.length, kept.fade_out.length) == (0.2, 0.15)


def test_a_split_keeps_the_fade_in_on_the_left_and_the_fade_out_on_the_right():
    p, clip = _looped()
    p = edits.set_fade(edits.set_fade(p, clip, "in", 0.2, "s-curve"), clip, "out", 0.15)
    p, right = edits.split_clip(p, clip, 1.1)
    left_clip, right_clip = p.find_clip(clip)[1], p.find_clip(right)[1]
    # the 0.1 s left part cannot hold the 0.2 s fade-in: it is cut to 0.1 s, shape kept
    assert left_clip.fade_in.length == pytest.approx(0.1) and left_clip.fade_out == Fade()
    assert left_clip.fade_in.shape == "s-curve"
    assert right_clip.fade_in == Fade() and right_clip.fade_out == Fade(0.15)
    assert (right_clip.start, right_clip.loop_phase) == (1.1, pytest.approx(0.0, abs=1e-12))


def test_trimming_a_reversed_stretched_clip_cuts_the_source_from_its_end():
    p, clip = _looped(1.0)
    p = edits.reverse_clip(edits.stretch_clip(p, clip, 2.0, "squeeze"), clip)  # 1.0..1.2
    c = edits.trim_clip(p, clip, 1.05, 1.15).find_clip(clip)[1]
    # played backwards at half speed: timeline 1.05..1.15 is source 0.075 down to 0.025
    assert (c.source_in, c.source_out) == (pytest.approx(0.025), pytest.approx(0.075))
