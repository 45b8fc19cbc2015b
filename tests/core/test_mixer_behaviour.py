"""Mixer behaviours that a cached re-render must keep: block edges, summing order, solo and mute.

Each re-render is compared with a render by a new Mixer (nothing cached), and values with sums
written out by hand.
"""

from __future__ import annotations

import importlib
import sys
from dataclasses import replace

import numpy as np
import pytest

from timeline import edits
from timeline.errors import HapticTimelineError, RenderError
from timeline.model import Project
from timeline.rendering.mixer import _LRU, BLOCK, Mixer, grid_length, piece_size
from timeline.signal.render_presets import QualityPreset
from timeline.tiles import SampledTile

RATE = 10_000.0
FULL = 0.18  # a drive track's full scale


def project_of(tracks: list[list[tuple[int, np.ndarray]]]) -> Project:
    """Drive tracks, each with clips (first sample, samples at RATE) on the grid."""
    project = edits.new_project(rate=RATE, templates=False)
    for clips in tracks:
        project, track = edits.add_track(project, "drive")
        for first, data in clips:
            project, tile = edits.add_tile(project, SampledTile(np.asarray(data, float), RATE))
            project, _ = edits.add_clip(project, track, tile, first / RATE)
    return project


def drive(mixer: Mixer, project: Project, n: int) -> np.ndarray:
    return mixer.render(project, 0.0, n / RATE)["drive"]


@pytest.mark.parametrize("first", [BLOCK - 1, BLOCK, 2 * BLOCK - 2, 3 * BLOCK - 1])
def test_an_edit_across_a_block_edge_updates_both_blocks(first: int) -> None:
    n = 4 * BLOCK
    project = project_of([[(first, [1.0, 2.0, 3.0])], [(10, [5.0])]])
    mixer = Mixer()
    drive(mixer, project, n)
    clip = project.tracks[0].clips[0]
    louder = edits.set_clip_gain(project, clip.id, 2.0)
    sums, hits = mixer.stats.block_sums, mixer.stats.block_hits
    out = drive(mixer, louder, n)
    touched = len({first // BLOCK, (first + 2) // BLOCK})  # the blocks of samples first..first+2
    assert mixer.stats.block_sums - sums == touched
    assert mixer.stats.block_hits - hits == 4 - touched
    want = np.zeros(n)
    want[10] = 5.0 * FULL
    want[first : first + 3] = np.array([1.0, 2.0, 3.0]) * (FULL * 2.0)
    assert np.array_equal(out, want)
    moved = edits.move_clip(louder, clip.id, (first + 1) / RATE)
    out = drive(mixer, moved, n)
    assert np.array_equal(out, drive(Mixer(), moved, n))
    assert out[first] == 0.0 and out[first + 3] == 3.0 * FULL * 2.0


def test_reordering_tracks_sums_in_the_new_order() -> None:
    # float addition is not associative, so the track order shows in the bits (terms that
    # cancel to far below their size are summed exactly instead: tests/stability/test_cancellation)
    a, b, c = FULL * 1.0, FULL * 1e-16, FULL * -0.5
    assert (a + b) + c != (a + c) + b
    n = 100
    project = project_of([[(0, [1.0] * 50)], [(0, [1e-16] * 50)], [(0, [-0.5] * 50)]])
    mixer = Mixer()
    assert drive(mixer, project, n)[0] == (a + b) + c
    reordered = edits.move_track(project, project.tracks[2].id, 1)
    out = drive(mixer, reordered, n)
    assert np.array_equal(out, drive(Mixer(), reordered, n))
    assert out[0] == (a + c) + b
    assert not out[50:].any()


def test_solo_and_mute_choose_the_tracks_that_sound() -> None:
    n = 10
    project = project_of([[(0, [1.0])], [(1, [2.0])], [(2, [4.0])]])
    a, b, c = (t.id for t in project.tracks)
    mixer = Mixer()
    assert drive(mixer, project, n)[:3].tolist() == [FULL, 2 * FULL, 4 * FULL]
    solo = edits.set_track(project, b, solo=True)
    assert drive(mixer, solo, n)[:3].tolist() == [0.0, 2 * FULL, 0.0]
    muted = edits.set_track(edits.set_track(solo, c, solo=True), b, mute=True)
    assert drive(mixer, muted, n)[:3].tolist() == [0.0, 0.0, 4 * FULL]
    only_a = mixer.render(project, 0.0, n / RATE, tracks=[a])["drive"]
    assert only_a[:3].tolist() == [FULL, 0.0, 0.0]
    with pytest.raises(HapticTimelineError, match="no track named 'x'"):
        mixer.render(project, 0.0, n / RATE, tracks=["x"])


def test_held_results_never_change_and_a_cleared_mixer_renders_alike() -> None:
    n = 2 * BLOCK
    project = project_of([[(5, [1.0, 1.0])]])
    mixer = Mixer()
    held = drive(mixer, project, n)
    kept = held.copy()
    louder = edits.set_clip_gain(project, project.tracks[0].clips[0].id, 3.0)
    again = drive(mixer, louder, n)
    assert np.array_equal(held, kept) and again[5] == 3.0 * FULL
    assert not held.flags.writeable and not again.flags.writeable
    mixer.clear()
    assert np.array_equal(drive(mixer, louder, n), again)


def test_a_clip_longer_than_a_piece_is_whole_and_exact() -> None:
    size = piece_size(RATE)
    assert size % 625 == 0 and (size / RATE) * RATE == size  # pieces start on exact offsets
    data = 1.0 + np.arange(2 * size + 7) % 97
    n = 2 * size + 20
    project = project_of([[(3, data)]])
    out = drive(Mixer(), project, n)
    want = np.zeros(n)
    want[3 : 3 + len(data)] = data * FULL
    assert np.array_equal(out, want)
    late = Mixer().render(project, (size - 5) / RATE, n / RATE)["drive"]
    assert np.array_equal(late, want[size - 5 :])


def test_piece_sizes_are_multiples_of_the_rates_odd_part() -> None:
    assert piece_size(10_000.0) == 40_000  # 625 * 64
    assert piece_size(192_000.0) == 48_000  # 375 * 128
    assert piece_size(44_100.0) == 44_100
    assert piece_size(1024.0) == 2**16
    assert piece_size(12.5) == 2**16  # not an integer rate


def test_grid_length_counts_samples_and_refuses_nonsense() -> None:
    assert grid_length(0.0, 1.0, RATE) == 10_000
    assert grid_length(0.25, 0.25, RATE) == 0
    for start, stop, rate in ((0.0, 1.0, 0.0), (1.0, 0.0, RATE), (0.0, float("nan"), RATE)):
        with pytest.raises(HapticTimelineError):
            grid_length(start, stop, rate)


def test_chunks_join_to_the_render_with_its_defaults_and_chosen_tracks() -> None:
    project = project_of([[(3, [1.0, 2.0])], [(6, [4.0] * 9)]])
    first = project.tracks[0].id
    mixer = Mixer()
    whole = mixer.render(project)["drive"]
    assert len(whole) == 15 and whole[3] == FULL
    pieces = list(mixer.render_chunks(project, chunk=4 / RATE))
    assert [t0 for t0, _ in pieces] == [0.0, 4 / RATE, 8 / RATE, 12 / RATE]
    assert np.array_equal(np.concatenate([p["drive"] for _, p in pieces]), whole)
    tiny = list(mixer.render_chunks(project, chunk=1e-9))  # under a sample: one sample each
    assert [len(p["drive"]) for _, p in tiny] == [1] * 15
    chosen = mixer.render_chunks(project, 0.0, 15 / RATE, RATE, tracks=[first], chunk=0.0005)
    joined = np.concatenate([p["drive"] for _, p in chosen])
    assert np.array_equal(joined, mixer.render(project, tracks=[first])["drive"])
    assert joined[3:5].tolist() == [FULL, 2 * FULL] and not joined[5:].any()


def test_the_shared_mixer_functions_pass_every_argument_on() -> None:
    from timeline.rendering import mixer as module

    project = project_of([[(3, [1.0, 2.0])], [(6, [4.0] * 9)]])
    first = project.tracks[0].id
    args = (project, 4 / RATE, 12 / RATE, 2 * RATE, "exact", [first])
    want = Mixer().render(*args)["drive"]
    assert np.array_equal(module.render(*args)["drive"], want)
    assert len(want) == 16 and want[0] != 0.0  # 0.4 to 1.2 ms at 20 kHz: only the first track
    assert np.array_equal(module.render(project)["drive"], Mixer().render(project)["drive"])
    assert module.render(project, context=True) == {}  # no context track
    chunks = module.render_chunks(*args, chunk=5 / (2 * RATE))
    assert np.array_equal(np.concatenate([c["drive"] for _, c in chunks]), want)
    starts = [t0 for t0, _ in module.render_chunks(project, chunk=5 / RATE)]
    assert starts == [0.0, 5 / RATE, 10 / RATE]


def test_the_cache_keeps_the_most_recently_used_within_its_bytes() -> None:
    cache: _LRU[str] = _LRU(400)  # values of at most a quarter of it are kept
    for key in "abcd":
        cache.put(key, key.upper(), 100)
    assert cache.bytes == 400 and cache.get("a") == "A"  # a is now the most recent
    cache.put("e", "E", 100)  # over the bound: the least recent (b) goes
    assert cache.get("b") is None and cache.get("a") == "A" and cache.bytes == 400
    cache.put("big", "X", 101)  # more than a quarter: not kept
    assert cache.get("big") is None and cache.bytes == 400
    assert cache.take("c") == "C" and cache.get("c") is None and cache.bytes == 300


def test_a_tracks_own_full_scale_replaces_its_kinds() -> None:
    project = project_of([[(0, [2.0])]])
    project = edits.set_track(project, project.tracks[0].id, full_scale=0.25, gain=0.5)
    assert drive(Mixer(), project, 2).tolist() == [2.0 * 0.5 * 0.25, 0.0]


def test_renders_too_long_or_of_the_wrong_axis_say_why() -> None:
    project = project_of([[(0, [1.0])]])
    with pytest.raises(HapticTimelineError, match="too many for one render"):
        Mixer().render(project, 0.0, (2**31 + 1) / RATE)
    torque = edits.add_track(edits.new_project("position", templates=False), "torque")[0]
    wrong = replace(project, tracks=project.tracks + tuple(
        replace(t, clips=project.tracks[0].clips) for t in torque.tracks))  # fmt: skip
    with pytest.raises(HapticTimelineError, match="is a torque track, which a time project cannot"):
        Mixer().render(wrong, 0.0, 0.001)


def test_numpy_and_compiled_adds_give_the_same_bits_after_an_edit(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    n = 3 * BLOCK
    data = np.sin(np.arange(5000) * 0.37) * 1e3
    project = project_of([[(100, data), (BLOCK - 7, data[:50])], [(2 * BLOCK + 1, data)]])
    clip = project.tracks[0].clips[1].id
    edited = edits.set_clip_gain(project, clip, 0.3)
    results = []
    for compiled in (False, True):
        if compiled:  # once loaded, the mixer adds with the compiled loop
            importlib.import_module("timeline.signal.render_kernels")
        else:  # the mixer adds with numpy until numba is loaded
            monkeypatch.delitem(sys.modules, "timeline.signal.render_kernels", raising=False)
        mixer = Mixer()
        drive(mixer, project, n)
        results.append(drive(mixer, edited, n))
        monkeypatch.undo()
    assert np.array_equal(results[0], results[1])
    assert np.array_equal(results[0], drive(Mixer(), edited, n))
    assert results[0][BLOCK - 7] == data[0] * (0.3 * FULL)


def test_clips_of_one_shape_are_evaluated_once_and_counted() -> None:
    n = 3 * BLOCK
    project = project_of([[(10, [1.0, 2.0])]])
    track, tile = project.tracks[0].id, project.tracks[0].clips[0].tile_id
    for first in (500, BLOCK + 3, 2 * BLOCK + 9):
        project, _ = edits.add_clip(project, track, tile, first / RATE)
    mixer = Mixer()
    out = drive(mixer, project, n)
    assert (mixer.stats.shape_renders, mixer.stats.clip_renders) == (1, 4)
    assert (mixer.stats.block_sums, mixer.stats.block_hits) == (3, 0)
    assert np.flatnonzero(out).tolist() == [10, 11, 500, 501, BLOCK + 3, BLOCK + 4,
                                            2 * BLOCK + 9, 2 * BLOCK + 10]  # fmt: skip
    drive(mixer, project, n)
    assert (mixer.stats.shape_renders, mixer.stats.clip_hits, mixer.stats.block_hits) == (1, 4, 3)


@pytest.mark.parametrize("first", [7, BLOCK + 7])
def test_an_overflowing_sum_names_the_first_sample_that_is_not_finite(first: int) -> None:
    project = project_of([[(first, [1e308, 1e308])], [(first + 1, [1e308])]])
    for track in project.tracks:  # full scale 1: 1e308 + 1e308 overflows
        project = edits.set_track(project, track.id, full_scale=1.0)
    with pytest.raises(RenderError, match=f"not a finite number at {(first + 1) / RATE:.6g}"):
        drive(Mixer(), project, 2 * BLOCK)
    mixer = Mixer()
    fine = edits.set_track(project, project.tracks[1].id, mute=True)
    drive(mixer, fine, 2 * BLOCK)  # cached, then a partial re-sum overflows
    with pytest.raises(RenderError, match=f"not a finite number at {(first + 1) / RATE:.6g}"):
        drive(mixer, project, 2 * BLOCK)


def test_one_render_counts_every_shape_and_every_layers_blocks() -> None:
    n = 3 * BLOCK
    project = project_of([[(10, [1.0, 2.0]), (BLOCK, [3.0])]])
    project, spring = edits.add_track(project, "stiffness")
    project, _ = edits.add_clip(project, spring, project.tracks[0].clips[0].tile_id, 0.0)
    mixer = Mixer()
    layers = mixer.render(project, 0.0, n / RATE)
    assert sorted(layers) == ["drive", "stiffness"]
    assert (mixer.stats.shape_renders, mixer.stats.block_sums) == (2, 6)


def test_a_float32_preset_is_the_float64_render_rounded_after_every_edit() -> None:
    f32 = QualityPreset("f32", "linear", "linear", 1, "float32")
    n = 3 * BLOCK
    project = project_of([[(10, [1.0 / 3.0] * 5), (BLOCK + 5, [2.0 / 3.0] * 5)]])
    mixer = Mixer()
    for step in range(3):
        out = mixer.render(project, 0.0, n / RATE, quality=f32)["drive"]
        want = Mixer().render(project, 0.0, n / RATE, quality="draft")["drive"]
        assert out.dtype == np.float32 and not out.flags.writeable
        assert np.array_equal(out, want.astype(np.float32)), step
        del out  # held by nobody: the next render updates the float32 copy in place
        clip = project.tracks[0].clips[step % 2].id
        project = edits.set_clip_gain(project, clip, 1.5 + step)


def test_grid_lengths_that_cannot_be_counted_say_so() -> None:
    with pytest.raises(HapticTimelineError, match="the render rate must be a finite number"):
        grid_length(0.0, 1.0, float("inf"))
    with pytest.raises(HapticTimelineError, match="more samples than can be counted"):
        grid_length(-1e300, 1e300, 1e300)
