"""Vibration designs read back from the timeline: joins, cuts, fades, emphasis, placements."""

import numpy as np
import pytest

from timeline import edits
from timeline.edits.vibration import (
    EDIT_TOLERANCE,
    Emphasis,
    VibrationDesign,
    VibrationTile,
    _cut,
    design_of,
    design_placements,
    emphasis_of,
    place_design,
    place_design_clip,
    sharpness_convention,
    with_emphasis,
)
from timeline.errors import EditError
from timeline.tiles import GeneratorTile

FLAT = VibrationDesign(((0.0, 0.5), (1.0, 0.5)), ((0.0, 0.2), (1.0, 0.6)), (), 1.0)
LOW = VibrationDesign(((0.0, 0.3), (1.0, 0.3)), ((0.0, 0.4),), (), 1.0)


def _new():
    return edits.new_project(templates=False)


def test_two_designs_apart_join_with_silence_between_them():
    p = place_design(place_design(_new(), FLAT), LOW, at=2.0)
    read = design_of(p)
    assert read.amplitude == (
        (0.0, 0.5),
        (1.0, 0.5),
        (1.0, 0.0),
        (2.0, 0.0),
        (2.0, 0.3),
        (3.0, 0.3),
    )
    assert read.frequency == ((0.0, 0.2), (1.0, 0.6), (2.0, 0.4))
    assert read.duration == 3.0 and read.emphasis == ()


def test_designs_that_touch_are_joined_exactly_not_analysed():
    p = place_design(_new(), FLAT)
    p, second = edits.add_track(p, "drive")
    p = place_design(p, LOW, at=1.0, track_id=second)
    read = design_of(p)
    assert read.amplitude == (
        (0.0, 0.5),
        (1.0, 0.5),
        (1.0, 0.0),
        (1.0, 0.0),
        (1.0, 0.3),
        (2.0, 0.3),
    )
    assert read.duration == 2.0


def test_a_silent_start_or_end_gets_no_extra_zero():
    quiet = VibrationDesign(((0.0, 0.0), (1.0, 0.0)), ((0.0, 0.5),), (), 1.0)
    p = place_design(place_design(_new(), quiet), quiet, at=2.0)
    assert design_of(p).amplitude == ((0.0, 0.0), (1.0, 0.0), (2.0, 0.0), (3.0, 0.0))


def test_cut_interpolates_the_ends_of_a_trimmed_range():
    amp = [(0.0, 0.0), (0.2, 1.0), (0.2, 0.4), (0.6, 0.4), (1.0, 0.0)]
    assert _cut(amp, 0.1, 0.8, outside=0.0) == [
        (0.1, 0.5), (0.2, 1.0), (0.2, 0.4), (0.6, 0.4), (0.8, pytest.approx(0.2))
    ]  # fmt: skip
    freq = [(0.0, 0.1), (1.0, 0.9)]
    assert _cut(freq, 0.25, 0.75, outside=None) == [
        (0.25, pytest.approx(0.3)),
        (0.75, pytest.approx(0.7)),
    ]
    assert _cut(freq, 0.0, 1.0, outside=None) == freq  # nothing cut
    assert _cut([], 0.2, 0.4, outside=0.0) == []
    # a range past the last point: the amplitude is `outside` there, the frequency holds
    assert _cut([(0.0, 0.3), (0.1, 0.3)], 0.15, 0.2, outside=0.0) == [(0.15, 0.0)]
    assert _cut([(0.0, 0.3), (0.1, 0.6)], 0.15, 0.2, outside=None) == [(0.15, 0.6)]
    # a point exactly on an end is kept, not doubled
    assert _cut(amp, 0.2, 0.6, outside=0.0) == [(0.2, 1.0), (0.2, 0.4), (0.6, 0.4)]


def test_a_trimmed_and_stretched_clip_maps_tile_seconds_to_the_timeline():
    p, clip = place_design_clip(_new(), FLAT, at=1.0)
    p = edits.trim_clip(p, clip, 1.25, 1.75)  # source 0.25..0.75
    read = design_of(edits.stretch_clip(p, clip, 1.1))
    # starts at 1.25, each tile second lasts 1.1: source 0.25..0.75 -> 1.25..1.8
    assert read.amplitude == ((1.25, 0.5), (pytest.approx(1.8), 0.5))
    hz = (80 + 150 * np.array([0.3, 0.5])) / 1.1  # 125 and 155 Hz, slowed
    assert [t for t, _ in read.frequency] == pytest.approx([1.25, 1.8])
    assert [f for _, f in read.frequency] == pytest.approx(list((hz - 80) / 150))
    fast = design_of(edits.stretch_clip(p, clip, 0.9))
    assert [t for t, _ in fast.amplitude] == pytest.approx([1.25, 1.7])
    # at twice the length 125 Hz plays at 62.5 Hz, below the carrier range: analysed instead
    slow = design_of(edits.stretch_clip(p, clip, 2.0))
    assert len(slow.amplitude) > 2 and slow.amplitude[0][0] < 1.25 + 0.01


def test_track_gain_and_full_scale_scale_the_breakpoints():
    p = place_design(_new(), FLAT)
    track = p.tracks[0].id
    half = design_of(edits.set_track(p, track, gain=0.5))
    assert [v for _, v in half.amplitude] == [0.25, 0.25]
    scaled = design_of(edits.set_track(p, track, full_scale=0.09))  # the drive kind's is 0.18
    assert [v for _, v in scaled.amplitude] == pytest.approx([0.25, 0.25])
    loud = design_of(edits.set_clip_gain(p, p.tracks[0].clips[0].id, 3.0))
    assert [v for _, v in loud.amplitude] == [1.0, 1.0]  # held at full scale
    inverted = design_of(edits.set_clip_gain(p, p.tracks[0].clips[0].id, -1.0))
    assert [v for _, v in inverted.amplitude] == [0.5, 0.5]


def test_a_fade_in_multiplies_the_envelope_within_the_tolerance():
    p, clip = place_design_clip(_new(), FLAT)
    read = design_of(edits.set_fade(p, clip, "in", 0.4))
    u = np.linspace(0.0, 1.0, 1001)
    expected = 0.5 * np.clip(u / 0.4, 0.0, 1.0)
    assert np.max(np.abs(read.amplitude_at(u) - expected)) <= EDIT_TOLERANCE + 1e-12
    assert read.amplitude[0] == (0.0, 0.0) and len(read.amplitude) <= 4
    assert read.frequency == FLAT.frequency  # a fade leaves the carrier alone


def test_a_fade_out_scales_a_design_s_own_emphasis_at_its_time():
    design = VibrationDesign(
        ((0.0, 0.5), (1.0, 0.5)), ((0.0, 0.5),), (Emphasis(0.8, 1.0, 0.5),), 1.0
    )
    p = _new()
    p, track = edits.add_track(p, "drive")
    p, tile = edits.add_tile(p, VibrationTile(design, "v", "", "sqrt"))
    p, clip = edits.add_clip(p, track, tile, 0.0)
    assert design_of(p).emphasis == (Emphasis(0.8, 1.0, 0.5),)
    faded = design_of(edits.set_fade(p, clip, "out", 0.4))  # 0.5 of the way through the fade
    (e,) = faded.emphasis
    assert (e.time, e.frequency) == (0.8, 0.5) and e.amplitude == pytest.approx(0.5)
    # trimmed to start at the emphasis it is kept; to end there it is not
    assert len(design_of(edits.trim_clip(p, clip, 0.8, 1.0)).emphasis) == 1
    assert design_of(edits.trim_clip(p, clip, 0.0, 0.8)).emphasis == ()


def test_emphasis_of_takes_the_clips_starting_within_the_span_ends_included():
    design = VibrationDesign(
        ((0.0, 0.5), (1.0, 0.5)), ((0.0, 0.5),),
        (Emphasis(0.0, 1.0, 0.5), Emphasis(1.0, 0.5, 0.5)), 1.0,
    )  # fmt: skip
    p, clip = place_design_clip(_new(), design, at=1.0)
    p = place_design(p, FLAT, at=2.5, track_id=p.tracks[0].id)  # no emphasis: no track added
    assert [t.name for t in p.tracks] == ["Drive 1", "Emphasis"]
    starts = [c.start for c in p.tracks[1].clips]
    assert starts == [1.0, 2.0]
    first, last = (c.id for c in p.tracks[1].clips)
    assert emphasis_of(p, clip) == [first, last]
    assert with_emphasis(p, [clip, first]) == [clip, first, last]
    moved = edits.move_clip(p, last, 2.01)
    assert emphasis_of(moved, clip) == [first]
    assert emphasis_of(p, first) == []  # an emphasis clip has none of its own
    # a sine clip on the Emphasis track is not an emphasis
    p, sine = edits.add_tile(p, GeneratorTile("sine", 0.01, (("frequency", 100.0),)))
    p, _ = edits.add_clip(p, p.tracks[1].id, sine, 1.5)
    assert emphasis_of(p, clip) == [first, last]


def test_an_emphasis_track_not_just_below_is_not_used():
    design = VibrationDesign(
        ((0.0, 0.5), (1.0, 0.5)), ((0.0, 0.5),), (Emphasis(0.5, 1.0, 0.5),), 1.0
    )
    p = place_design(_new(), design)
    p, other = edits.add_track(p, "drive")
    p = edits.move_track(p, other, 0)  # above Drive 1, whose Emphasis is index 2
    p = place_design(p, design, track_id=other)
    names = [t.name for t in p.tracks]
    assert names == ["Drive 3", "Emphasis", "Drive 1", "Emphasis"]  # an Emphasis track counts
    assert [len(t.clips) for t in p.tracks] == [1, 1, 1, 1]


def test_a_design_goes_on_a_drive_track_only():
    p, other = edits.add_track(_new(), "stiffness")
    with pytest.raises(EditError, match="^a vibration design goes on a drive track$"):
        place_design(p, FLAT, track_id=other)
    q = place_design(p, FLAT)  # the first drive track, added
    assert [t.kind for t in q.tracks] == ["stiffness", "drive"]


def test_design_placements_are_the_envelopes_and_each_emphasis():
    design = VibrationDesign(
        ((0.0, 0.5), (1.0, 0.5)), ((0.0, 0.5),), (Emphasis(0.5, 0.7, 1.0),), 1.0
    )
    got = design_placements(design, "name", "src", "linear", ("a note",))
    first, accent = got.placements
    assert first.kind == "drive" and first.tile.design == VibrationDesign(
        design.amplitude, design.frequency, (), 1.0
    )
    assert (first.tile.name, first.tile.source, first.tile.sharpness) == ("name", "src", "linear")
    assert (accent.start, accent.kind, accent.track) == (0.5, "drive", "emphasis")
    assert dict(accent.tile.params) == {"amplitude": 0.7, "frequency": 1.0}
    assert [(t.key, t.name, t.kind) for t in got.tracks] == [("emphasis", "Emphasis", "drive")]
    assert got.notes == ("a note",)
    plain = design_placements(FLAT, "n", "", "sqrt")
    assert len(plain.placements) == 1 and plain.tracks == ()


def test_sharpness_convention_is_the_first_design_s():
    p = place_design_clip(_new(), FLAT, sharpness="linear")[0]
    assert sharpness_convention(p) == "linear"
    assert sharpness_convention(_new()) == "sqrt"


def test_short_sine_clips_are_read_as_emphasis_longer_ones_are_not():
    p = place_design(_new(), FLAT)
    track = p.tracks[0].id
    params = (("frequency", 155.0), ("amplitude", 0.4))
    p, short = edits.add_tile(p, GeneratorTile("sine", 0.05, params))
    p, clip = edits.add_clip(p, track, short, 2.0)
    (e,) = design_of(p).emphasis
    assert (e.time, e.frequency) == (2.0, 0.5) and e.amplitude == pytest.approx(0.4)
    doubled = design_of(edits.stretch_clip(edits.set_clip_gain(p, clip, 0.5), clip, 0.5))
    # squeezed to 25 ms it plays 310 Hz, above the range: held at 1
    assert doubled.emphasis[0].frequency == 1.0
    assert doubled.emphasis[0].amplitude == pytest.approx(0.2)
    p, long_ = edits.add_tile(p, GeneratorTile("sine", 0.06, params))
    p, _ = edits.add_clip(p, track, long_, 3.0)
    assert [e.time for e in design_of(p).emphasis] == [2.0]


def test_emphasis_clips_at_one_time_keep_their_placing_order_past_nine():
    design = VibrationDesign(
        ((0.0, 0.5), (1.0, 0.5)), ((0.0, 0.5),),
        tuple(Emphasis(0.5, 0.05 * (k + 1), 0.5) for k in range(12)), 1.0,
    )  # fmt: skip
    read = design_of(place_design(_new(), design))
    assert [e.amplitude for e in read.emphasis] == pytest.approx(
        [0.05 * (k + 1) for k in range(12)]
    )


def test_a_silent_analysed_layer_reads_as_silence():
    quiet = VibrationDesign(((0.0, 0.0), (1.0, 0.0)), ((0.0, 0.3),), (), 1.0)
    p, clip = place_design_clip(_new(), quiet, at=0.5)
    read = design_of(edits.reverse_clip(p, clip), rate=1000.0)  # reversed: analysed
    assert read.amplitude == ((0.0, 0.0), (1.5, 0.0))
    assert read.frequency == ((0.0, 0.5),) and read.duration == 1.5


def test_a_project_without_drive_clips_has_no_design():
    p, _ = edits.add_track(_new(), "drive")
    with pytest.raises(EditError) as refused:
        design_of(p)
    assert str(refused.value) == "the project has no sounding drive track with clips"


def test_an_analysed_design_is_read_at_the_rate_asked_for():
    p, clip = place_design_clip(_new(), FLAT)
    p = edits.reverse_clip(p, clip)
    coarse = design_of(p, rate=200.0)
    ticks = np.array([t for t, _ in coarse.amplitude + coarse.frequency]) * 200.0
    assert np.allclose(ticks, np.round(ticks), atol=1e-6)  # on the 5 ms grid
    fine = design_of(p, rate=7919.0)
    assert fine != coarse


def test_the_analysis_renders_only_the_tracks_asked_for():
    p, clip = place_design_clip(_new(), FLAT)
    p = edits.reverse_clip(p, clip)  # analysed
    alone = design_of(p, rate=2000.0)
    p, other = edits.add_track(p, "drive")
    p = place_design(p, LOW, track_id=other)
    first = design_of(p, [p.tracks[0].id], rate=2000.0)
    assert first == alone


def test_a_repeated_emphasis_clip_is_no_emphasis():
    design = VibrationDesign(((0.0, 0.5), (1.0, 0.5)), ((0.0, 0.5),), (Emphasis(0.5, 1, 0.5),), 1.0)
    p = place_design(_new(), design)
    accent = p.tracks[1].clips[0].id
    assert len(design_of(p).emphasis) == 1
    # looped 1.2 times (its 155 Hz would still be in range squeezed so): no longer one pulse
    looped = design_of(edits.stretch_clip(p, accent, 1.2, "repeat"), rate=2000.0)
    assert looped.emphasis == ()


def test_a_carrier_stretched_to_just_the_top_of_its_range_stays_exact():
    top = VibrationDesign(((0.0, 0.5), (1.0, 0.5)), ((0.0, 1.0),), (), 1.0)
    p, clip = place_design_clip(_new(), top)
    # 230 Hz sped up by a part in 10^12 is within the 1e-9 Hz allowance: read exactly
    read = design_of(edits.stretch_clip(p, clip, 1 - 1e-12))
    assert read.amplitude == ((0.0, 0.5), (pytest.approx(1.0), 0.5))
    assert read.frequency[0][1] == pytest.approx(1.0)


def test_a_looped_design_clip_is_analysed_not_squeezed():
    ramp = VibrationDesign(((0.0, 0.0), (1.0, 1.0)), ((0.0, 0.6),), (), 1.0)
    p, clip = place_design_clip(_new(), ramp)
    read = design_of(edits.stretch_clip(p, clip, 2.0, "repeat"), rate=2000.0)
    # a sawtooth played twice, not one ramp over two seconds (0.25 and 0.75 there)
    at = read.amplitude_at(np.array([0.5, 1.5]))
    assert at == pytest.approx([0.5, 0.5], abs=0.05)


def test_a_later_design_rising_from_silence_gets_no_extra_zero():
    rise = VibrationDesign(((0.0, 0.0), (1.0, 0.5)), ((0.0, 0.5),), (), 1.0)
    p = place_design(place_design(_new(), FLAT), rise, at=2.0)
    assert design_of(p).amplitude == ((0.0, 0.5), (1.0, 0.5), (1.0, 0.0), (2.0, 0.0), (3.0, 0.5))
