"""Exact values of clip operations through the mixer."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from timeline import edits, render
from timeline.model import Clip, Fade
from timeline.rendering.clip_render import _apply_fades
from timeline.signal.fades import fade_envelope, fade_in_gain
from timeline.tiles import SampledTile, generator, spline

from .helpers import one_clip

FULL = 0.18  # drive full scale, N*m
RATE = 10_000


def drive(p, **kw):
    return render(p, **kw)["drive"]


def test_gain_scales_every_sample():
    p, clip = one_clip(generator("sine", 1.0, frequency=10))
    base = drive(p)
    np.testing.assert_allclose(drive(edits.set_clip_gain(p, clip, 0.25)), 0.25 * base, atol=1e-17)


def test_scale_about_a_pivot_line_keeps_the_line_fixed():
    p, clip = one_clip(generator("constant", 1.0, value=0.2))
    p2 = edits.scale_clip(p, clip, 3.0, pivot=0.5)  # 0.5 + 3*(0.2-0.5) = -0.4
    np.testing.assert_allclose(drive(p2), -0.4 * FULL, rtol=1e-12)
    p3 = edits.scale_clip(p2, clip, 0.5, pivot=0.5)  # 0.5 + 0.5*(-0.4-0.5) = 0.05
    np.testing.assert_allclose(drive(p3), 0.05 * FULL, rtol=1e-12)


def test_invert_about_the_pivot_line_and_twice_is_identity():
    p, clip = one_clip(generator("sine", 1.0, frequency=3))
    base = drive(p)
    inv = edits.invert_clip(edits.set_pivot(p, clip, 0.25), clip)
    np.testing.assert_allclose(drive(inv), 2 * 0.25 * FULL - base, atol=1e-15)
    assert inv.find_clip(clip)[1].inverted
    np.testing.assert_allclose(drive(edits.invert_clip(inv, clip)), base, atol=1e-15)


def test_reverse_of_a_sampled_tile_is_the_samples_backwards():
    data = np.random.default_rng(1).normal(size=777)
    p, clip = one_clip(SampledTile(data, RATE))
    np.testing.assert_array_equal(drive(edits.reverse_clip(p, clip)), FULL * data[::-1])


def test_reverse_of_a_ramp_runs_down():
    p, clip = one_clip(generator("ramp", 1.0, start=0.0, end=1.0))
    out = drive(edits.reverse_clip(p, clip))
    t = np.arange(RATE) / RATE
    np.testing.assert_allclose(out, FULL * (1.0 - t), atol=1e-15)


@pytest.mark.parametrize(
    ("shape", "mid"),
    [
        ("linear", 0.5),
        ("equal-power", np.sqrt(0.5)),
        ("exponential", (np.sqrt(1000) - 1) / 999),
        ("s-curve", 0.5),
    ],
)
def test_fade_shapes_at_their_midpoint(shape, mid):
    p, clip = one_clip(generator("constant", 1.0, value=1.0))
    p = edits.set_fade(p, clip, "in", 0.2, shape)
    p = edits.set_fade(p, clip, "out", 0.4, shape)
    out = drive(p) / FULL
    assert out[0] == 0.0
    assert out[1000] == pytest.approx(mid, abs=1e-12)  # half-way through the fade-in at 0.1 s
    assert out[8000] == pytest.approx(mid, abs=1e-12)  # half-way through the fade-out at 0.8 s
    assert out[5000] == 1.0
    assert fade_in_gain(np.array([1.0]), shape)[0] == pytest.approx(1.0)


def test_zero_length_fade_is_no_fade():
    p, clip = one_clip(generator("constant", 1.0, value=1.0))
    out = drive(edits.set_fade(p, clip, "in", 0.0, "exponential"))
    assert np.isfinite(out).all() and out[0] == FULL


def test_stretching_a_10hz_sine_by_two_gives_5hz():
    p, clip = one_clip(generator("sine", 1.0, frequency=10))
    out = drive(edits.stretch_clip(p, clip, 2.0))
    t = np.arange(2 * RATE) / RATE
    assert len(out) == 2 * RATE
    np.testing.assert_allclose(out, FULL * np.sin(2 * np.pi * 5 * t), atol=1e-14)
    spectrum = np.abs(np.fft.rfft(out))
    assert np.argmax(spectrum) * RATE / len(out) == 5.0


def test_repeat_mode_loops_the_source_at_its_own_speed():
    data = np.arange(100, dtype=float)
    p, clip = one_clip(SampledTile(data, RATE))
    out = drive(edits.stretch_clip(p, clip, 3.0, "repeat"))
    np.testing.assert_array_equal(out, FULL * np.tile(data, 3))


def test_split_then_render_equals_the_original():
    for tile in (
        generator("chirp", 1.0, f0=5, f1=50),
        SampledTile(np.random.default_rng(2).normal(size=9000), RATE),
    ):
        p, clip = one_clip(tile, start=0.5)
        p = edits.set_fade(p, clip, "in", 0.1, "s-curve")
        p = edits.set_fade(p, clip, "out", 0.1, "linear")
        base = drive(p)
        p2, right = edits.split_clip(p, clip, 0.9)
        assert len(p2.tracks[0].clips) == 2
        np.testing.assert_allclose(drive(p2), base, atol=1e-15)


def test_split_of_a_reversed_stretched_clip_renders_the_same():
    p, clip = one_clip(generator("saw", 1.0, frequency=3))
    p = edits.stretch_clip(edits.reverse_clip(p, clip), clip, 1.5)
    base = drive(p)
    p2, _ = edits.split_clip(p, clip, 0.61)
    np.testing.assert_allclose(drive(p2), base, atol=1e-12)


def test_merge_equals_the_sum_of_its_parts():
    p, a = one_clip(generator("sine", 1.0, frequency=4))
    track = p.tracks[0].id
    p, t2 = edits.add_track(p, "drive", gain=0.5)
    p, tile = edits.add_tile(p, spline([(0, 0), (0.3, 1), (0.6, -0.5)], 0.6))
    p, b = edits.add_clip(p, t2, tile, 0.2)
    base = drive(p)
    merged, tile_id = edits.merge_clips(p, [a, b])
    assert [len(t.clips) for t in merged.tracks] == [1, 0]
    assert merged.tracks[0].id == track and tile_id in merged.tab("Scratch").tile_ids
    np.testing.assert_allclose(drive(merged), base, atol=1e-15)


def test_merge_refuses_clips_of_different_kinds():
    p, a = one_clip(generator("sine", 1.0))
    p, t = edits.add_track(p, "stiffness")
    p, b = edits.add_clip(p, t, p.tracks[0].clips[0].tile_id, 0.0)
    with pytest.raises(edits.EditError, match="one kind"):
        edits.merge_clips(p, [a, b])


def test_two_tracks_of_one_kind_superpose():
    p, a = one_clip(generator("sine", 1.0, frequency=10))
    p, t2 = edits.add_track(p, "drive")
    p, tile = edits.add_tile(p, generator("constant", 1.0, value=0.5))
    p, _ = edits.add_clip(p, t2, tile, 0.0)
    t = np.arange(RATE) / RATE
    np.testing.assert_allclose(drive(p), FULL * (np.sin(2 * np.pi * 10 * t) + 0.5), atol=1e-15)


def test_mute_and_solo_choose_what_sounds():
    p, a = one_clip(generator("constant", 1.0, value=1.0))
    p, t2 = edits.add_track(p, "drive")
    p, tile = edits.add_tile(p, generator("constant", 1.0, value=2.0))
    p, _ = edits.add_clip(p, t2, tile, 0.0)
    first = p.tracks[0].id
    assert drive(p)[0] == pytest.approx(3 * FULL)
    assert drive(edits.set_track(p, first, mute=True))[0] == pytest.approx(2 * FULL)
    assert drive(edits.set_track(p, first, solo=True))[0] == pytest.approx(FULL)
    assert render(edits.set_track(edits.set_track(p, first, mute=True), t2, mute=True)) == {}


def test_only_layers_with_clips_are_rendered():
    p, _ = one_clip(generator("sine", 1.0), kind="stiffness")
    p, _ = edits.add_track(p, "mass")
    assert set(render(p)) == {"stiffness"}


def test_moving_a_clip_to_another_kind_changes_its_meaning():
    p, clip = one_clip(generator("constant", 1.0, value=1.0))
    p, stiff = edits.add_track(p, "stiffness")
    moved = edits.move_clip(p, clip, start=0.5, track_id=stiff)
    layers = render(moved)
    assert set(layers) == {"stiffness"}
    assert layers["stiffness"][5000] == 1.0 and layers["stiffness"][4999] == 0.0


def test_sampled_tile_at_another_rate_is_resampled_band_limited():
    rate_in = 48_000
    t = np.arange(rate_in) / rate_in
    tone = np.sin(2 * np.pi * 100 * t) + 0.5 * np.sin(2 * np.pi * 9000 * t)  # 9 kHz aliases at 10k
    p, _ = one_clip(SampledTile(tone, rate_in))
    out = drive(p) / FULL
    ref = np.sin(2 * np.pi * 100 * np.arange(RATE) / RATE)
    interior = slice(500, -500)
    assert np.abs(out[interior] - ref[interior]).max() < 1e-3  # 9 kHz removed, 100 Hz kept
    draft = render(p, quality="draft")["drive"] / FULL
    assert np.abs(draft[interior] - ref[interior]).max() > 0.1  # linear interpolation aliases


FADE_SHAPES = st.sampled_from(["linear", "equal-power", "exponential", "s-curve"])


@settings(max_examples=100, deadline=None)
@given(
    st.floats(0.01, 3.0),
    st.floats(0.0, 1.0),
    st.floats(0.0, 1.0),
    FADE_SHAPES,
    FADE_SHAPES,
    st.floats(0.0, 1.0),
    st.sampled_from([1_000.0, 10_000.0, 44_100.0]),
)
def test_fades_touch_only_where_their_gain_is_not_1_with_the_same_bits(
    duration, fade_in, fade_out, in_shape, out_shape, start, rate
):
    """Overlapping or separate fades, a window starting anywhere in the clip: the gains applied
    span by span equal the whole clip multiplied by both envelopes, sample for sample."""
    clip = Clip(
        "c", "t", 0.0, 0.0, duration,
        fade_in=Fade(fade_in * duration, in_shape), fade_out=Fade(fade_out * duration, out_shape),
    )  # fmt: skip
    pos0 = start * duration
    n = max(1, int((duration - pos0) * rate))
    values = np.cos(np.arange(n) * 0.01) + 2.0
    expected = values * (
        fade_envelope(pos0 + np.arange(n) / rate, duration, clip.fade_in, clip.fade_out)
        if clip.fade_in.length > 0 or clip.fade_out.length > 0
        else 1.0
    )
    _apply_fades(values, clip, pos0, rate)
    assert np.array_equal(values, expected)
