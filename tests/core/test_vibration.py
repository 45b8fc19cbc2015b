"""Vibration designs on the timeline: exact read-back, the synthesised carrier, edits, the file."""

import json

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from timeline import edits
from timeline.edits import tile_params, tile_shape
from timeline.edits.vibration import (
    EDIT_TOLERANCE,
    Emphasis,
    VibrationDesign,
    VibrationTile,
    design_of,
    place_design,
)
from timeline.errors import EditError, ProjectFileError
from timeline.files import projectfile
from timeline.plugins.track_kinds import track_kind
from timeline.rendering import mixer
from timeline.signal.vibration_design import F_MAX, F_MIN, carrier_hz
from timeline.tiles import generator

RATE = 10_000.0
DESIGN = VibrationDesign(
    amplitude=((0.0, 0.0), (0.2, 1.0), (0.2, 0.4), (0.6, 0.4), (1.0, 0.0)),  # a step at 0.2 s
    frequency=((0.0, 0.1), (1.0, 0.9)),
    emphasis=(Emphasis(0.5, 1.0, 0.7), Emphasis(0.5, 0.6, 0.2)),  # two at one time
    duration=1.0,
)


def _project(design=DESIGN, **kwargs):
    return place_design(edits.new_project(templates=False), design, **kwargs)


def _drive(project, start=0.0, stop=None):
    stop = project.duration if stop is None else stop
    layer = mixer.render(project, start, stop, RATE, "normal")["drive"]
    return layer / track_kind("drive").full_scale


def test_an_unedited_design_reads_back_exactly_wherever_it_is_placed():
    assert design_of(_project()) == DESIGN
    later = design_of(_project(at=1.5))
    assert later.amplitude == tuple((t + 1.5, v) for t, v in DESIGN.amplitude)
    assert [(e.time, e.amplitude) for e in later.emphasis] == [(2.0, 1.0), (2.0, 0.6)]
    assert later.duration == 2.5


def test_the_carrier_phase_is_the_exact_integral_of_the_frequency_envelope():
    # 80 + 150 * (0.1 + 0.8 t) Hz integrates to 155 cycles over the first second
    assert DESIGN.cycles(np.array([1.0]))[0] == pytest.approx(155.0, abs=1e-9)
    t = np.linspace(0.0, 1.0, 200_001)
    numeric = np.concatenate(
        [[0.0], np.cumsum(np.diff(t) * carrier_hz(0.1 + 0.4 * (t[1:] + t[:-1])))]
    )
    assert np.max(np.abs(DESIGN.cycles(t) - numeric)) < 1e-9


def test_rendered_values_are_the_envelope_times_the_carrier_at_any_rate():
    p = _project()
    x = _drive(p)
    u = np.arange(len(x)) / RATE
    outside_emphasis = (u < 0.5) | (u >= 0.5 + 2 / carrier_hz(0.2))
    expected = DESIGN.amplitude_at(u) * np.sin(2 * np.pi * DESIGN.cycles(u))
    assert np.max(np.abs(x - expected)[outside_emphasis]) < 1e-9
    # peak level follows the envelope: 0.4 between 0.25 s and 0.45 s
    assert np.max(np.abs(x[2500:4500])) == pytest.approx(0.4, abs=2e-3)
    # a different rate samples the same curve: shared instants agree
    y = mixer.render(p, 0.0, p.duration, 3 * RATE, "normal")["drive"] / 0.18
    assert np.max(np.abs(y[::3][: len(x)] - x)) < 1e-9


def test_an_emphasis_is_a_clip_of_its_own_that_adds_two_cycles_to_the_carrier():
    design = VibrationDesign(
        ((0.0, 0.3), (0.1, 0.3)), ((0.0, 0.5),), (Emphasis(0.05, 0.9, 1.0),), 0.1
    )
    p = _project(design)
    assert [t.name for t in p.tracks] == ["Drive 1", "Emphasis"]
    (accent,) = p.tracks[1].clips
    assert (accent.start, accent.duration) == (0.05, 2 / F_MAX)
    x = _drive(p)
    envelope_only = _drive(edits.set_track(p, p.tracks[1].id, mute=True))
    pulse = (x - envelope_only)[500:]
    n = int(round(2 / F_MAX * RATE))  # two cycles of 230 Hz: 87 samples
    # full for the first cycle, fading linearly over the second, silent after
    assert np.max(np.abs(pulse[: n // 2])) == pytest.approx(0.9, abs=0.01)
    assert np.max(np.abs(pulse[n // 2 + 22 : n])) < 0.5 * 0.9
    assert not np.any(pulse[n + 1 :])
    assert np.max(np.abs(envelope_only)) == pytest.approx(0.3, abs=0.01)


def test_gain_trim_and_stretch_are_applied_to_the_breakpoints_exactly():
    p = _project()
    clip = p.tracks[0].clips[0].id
    half = design_of(edits.set_clip_gain(p, clip, 0.5))
    assert [v for _, v in half.amplitude] == [v * 0.5 for _, v in DESIGN.amplitude]
    assert [e.amplitude for e in half.emphasis] == [1.0, 0.6]  # clips of their own
    trimmed = design_of(edits.trim_clip(p, clip, 0.1, 0.8))
    assert trimmed.amplitude[0] == (0.1, 0.5) and trimmed.amplitude[-1] == pytest.approx((0.8, 0.2))
    slow = design_of(edits.stretch_clip(p, clip, 1.1))
    assert slow.amplitude[1] == pytest.approx((0.22, 1.0))
    # the carrier is resampled too: 80 + 150 * 0.9 = 215 Hz becomes 195.5 Hz
    assert slow.frequency[-1][1] == pytest.approx((215 / 1.1 - F_MIN) / (F_MAX - F_MIN))
    # slower still, 95 Hz would fall below the carrier range: the layer is analysed instead
    slower = design_of(edits.stretch_clip(p, clip, 1.5))
    assert slower.frequency[0][1] == 0.0 and len(slower.amplitude) > len(DESIGN.amplitude)


def test_emphasis_clip_edits_are_read_back_as_the_edited_emphasis():
    p = _project()
    strong, weak = (c.id for c in p.tracks[1].clips)  # both at 0.5 s
    p = edits.move_clip(p, weak, 0.6)
    p = edits.set_clip_gain(p, strong, 0.5)
    p = edits.set_track(p, p.tracks[1].id, gain=0.8)
    read = [(e.time, e.amplitude, e.frequency) for e in design_of(p).emphasis]
    assert read == [(0.5, pytest.approx(0.4), 0.7), (0.6, pytest.approx(0.48), 0.2)]
    # squeezed to 1/1.1: 80 + 150 * 0.7 = 185 Hz plays at 203.5 Hz
    squeezed = design_of(edits.stretch_clip(p, strong, 1 / 1.1))
    (fast,) = [e for e in squeezed.emphasis if e.time == 0.5]
    assert fast.frequency == pytest.approx((185 * 1.1 - F_MIN) / (F_MAX - F_MIN))
    p = edits.remove_clip(p, weak)
    p, copy = edits.duplicate_clip(p, strong, 0.9)
    assert [e.time for e in design_of(p).emphasis] == [0.5, 0.9]
    # reversed, it is no longer an emphasis: the layer is analysed, the other stays exact
    reversed_ = design_of(edits.reverse_clip(p, copy))
    assert [e.time for e in reversed_.emphasis] == [0.5] and reversed_.amplitude != DESIGN.amplitude


def test_an_emphasis_tile_s_parameters_are_its_emphasis_and_set_its_length():
    p = _project()
    clip = p.tracks[1].clips[0]
    p = tile_params.set_param(p, clip.tile_id, "frequency", 0.0)  # 185 Hz -> 80 Hz
    p = tile_params.set_param(p, clip.tile_id, "amplitude", 0.25)
    longer = p.find_clip(clip.id)[1]
    assert longer.duration == 2 / F_MIN  # the clip plays all of the longer pulse
    assert design_of(p).emphasis[0] == Emphasis(0.5, 0.25, 0.0)
    x = _drive(edits.set_track(p, p.tracks[0].id, mute=True))
    assert np.any(x[5000 + 240 : 5000 + 249]) and not np.any(x[5000 + 251 :])  # 25 ms: 250
    with pytest.raises(EditError, match="lasts 0.025 s, as its parameters say"):
        tile_params.set_length(p, clip.tile_id, 0.5)


def test_amplitude_breakpoints_are_edited_as_points_and_read_back_exactly():
    p = _project()
    tile = p.tracks[0].clips[0].tile_id
    p = tile_shape.move_point(p, tile, 3, 0.7, 1.7)  # (0.6, 0.4) -> (0.7, 1.0): clamped to 1
    p = tile_shape.move_point(p, tile, 1, 0.5, 0.9)  # one side of the step at 0.2 s stays on it
    p, k = tile_shape.add_point(p, tile, 0.9, 0.25)
    p = tile_shape.remove_point(p, tile, 0)
    assert k == 4
    assert design_of(p).amplitude == ((0.2, 0.9), (0.2, 0.4), (0.7, 1.0), (0.9, 0.25), (1.0, 0.0))
    with pytest.raises(EditError, match="inside the tile"):
        tile_shape.add_point(p, tile, 1.5, 0.5)


def test_a_fade_is_reduced_to_breakpoints_within_the_stated_bound():
    ramp = VibrationDesign(((0.0, 1.0), (1.0, 1.0)), ((0.0, 0.5),), (), 1.0)
    p = _project(ramp)
    clip = p.tracks[0].clips[0].id
    faded = design_of(edits.set_fade(p, clip, "out", 0.5, "equal-power"))
    t = np.linspace(0.0, 1.0, 10_001)
    exact = np.where(t < 0.5, 1.0, np.sin(0.5 * np.pi * np.clip((1.0 - t) / 0.5, 0, 1)))
    assert np.max(np.abs(faded.amplitude_at(t) - exact)) <= EDIT_TOLERANCE + 1e-12
    assert len(faded.amplitude) < 40


def test_other_clips_are_analysed_and_short_sines_read_as_emphasis():
    p = _project(VibrationDesign(((0.0, 0.5), (0.3, 0.5)), ((0.0, 0.5),), (), 0.3))
    track = p.tracks[0].id
    p, tile = edits.add_tile(p, generator("sine", 0.02, frequency=230.0))
    p, _ = edits.add_clip(p, track, tile, 0.5, gain=0.8)
    read = design_of(p)
    assert read.amplitude == ((0.0, 0.5), (0.3, 0.5))
    assert read.emphasis == (Emphasis(0.5, 0.8, 1.0),)
    # an overlapping sine makes the layer a mixture: analysed, not exact
    p, tone = edits.add_tile(p, generator("sine", 0.3, frequency=155.0, amplitude=0.2))
    p, _ = edits.add_clip(p, track, tone, 0.0)
    mixed = design_of(p)
    assert mixed.amplitude != read.amplitude and len(mixed.amplitude) >= 2


def test_a_silent_design_keeps_its_frequency_envelope():
    silent = VibrationDesign(((0.0, 0.0), (2.0, 0.0)), ((0.0, 0.2), (2.0, 0.8)), (), 2.0)
    assert design_of(_project(silent)) == silent
    assert not np.any(_drive(_project(silent)))


@pytest.mark.parametrize(
    ("amplitude", "frequency", "message"),
    [
        (((0.0, 1.5),), (), "between 0 and 1"),
        (((0.5, 0.1), (0.2, 0.1)), (), "goes back in time"),
        (((0.0, float("nan")),), (), "between 0 and 1"),
        (((0.0, 0.1), (3.0, 0.1)), (), "has a breakpoint at 3 s"),
    ],
)
def test_bad_designs_are_refused_in_one_sentence(amplitude, frequency, message):
    with pytest.raises(EditError, match=message):
        VibrationDesign(amplitude, frequency, (), 1.0)


def test_a_design_goes_on_a_drive_track_only():
    p, track = edits.add_track(edits.new_project(templates=False), "stiffness")
    with pytest.raises(EditError, match="drive track"):
        place_design(p, DESIGN, track_id=track)


def test_the_project_file_keeps_the_design_and_refuses_a_damaged_one(tmp_path):
    path = tmp_path / "v.htl"
    projectfile.save(_project(at=0.25), path)
    assert design_of(projectfile.load(path)) == DESIGN.shifted(0.25)
    doc = json.loads(path.read_text())
    tile = next(t for t in doc["project"]["tiles"].values() if t["type"] == "vibration")
    assert tile["emphasis"] == []  # each emphasis is a clip of its own
    accents = [t["params"] for t in doc["project"]["tiles"].values() if t["type"] == "generator"]
    assert accents == [{"amplitude": 1.0, "frequency": 0.7}, {"amplitude": 0.6, "frequency": 0.2}]
    tile["amplitude"][1] = [0.2, 7.0]
    path.write_text(json.dumps(doc))
    with pytest.raises(ProjectFileError, match="between 0 and 1"):
        projectfile.load(path)


def test_a_schema_1_file_still_loads(tmp_path):
    path = tmp_path / "old.htl"
    projectfile.save(edits.new_project(), path)
    doc = json.loads(path.read_text())
    doc["schema"] = 1
    path.write_text(json.dumps(doc))
    assert projectfile.load(path) == edits.new_project()


unit = st.floats(0.0, 1.0)
times = st.lists(st.floats(0.0, 5.0), min_size=0, max_size=12).map(sorted)


@st.composite
def designs(draw):
    amp = [(t, draw(unit)) for t in draw(times)]
    freq = [(t, draw(unit)) for t in draw(times)]
    accents = [Emphasis(t, draw(unit), draw(unit)) for t in draw(times)]
    return VibrationDesign(tuple(amp), tuple(freq), tuple(accents), 5.0)


@settings(max_examples=40, deadline=None)
@given(designs(), st.floats(0.0, 3.0))
def test_any_design_survives_placing_saving_and_loading(design, at):
    p = _project(design, at=at)
    q = projectfile.from_json(json.loads(projectfile.dumps(p)))
    assert design_of(q) == design_of(p)
    if at == 0.0:
        assert design_of(q) == design
    assert any(isinstance(t, VibrationTile) for t in q.tiles.values())


coarse_times = st.lists(st.floats(0.0, 5.0).map(lambda t: round(t, 3)), max_size=12).map(sorted)


@st.composite
def coarse_designs(draw):
    """Designs on a 1 ms grid, so a step's two sides are told apart after shifting."""
    amp = [(t, draw(unit)) for t in draw(coarse_times)]
    accents = [Emphasis(t, draw(unit), draw(unit)) for t in draw(coarse_times)]
    return VibrationDesign(tuple(amp), ((0.0, 0.5),), tuple(accents), 5.0)


@settings(max_examples=40, deadline=None)
@given(
    coarse_designs(),
    st.floats(0.0, 1.0),
    st.floats(0.0, 2.0).map(lambda t: round(t, 3)),
    st.floats(0.0, 0.4).map(lambda t: round(t, 3)),
    st.floats(0.0, 0.4).map(lambda t: round(t, 3)),
)
def test_gain_trim_and_fades_read_back_as_the_edited_envelope(design, gain, at, cut, fade):
    p = _project(design, at=at)
    clip = p.tracks[0].clips[0].id
    p = edits.set_clip_gain(p, clip, gain)
    p = edits.trim_clip(p, clip, at + cut, None)
    length = p.tracks[0].clips[0].duration
    p = edits.set_fade(p, clip, "out", min(fade, length), "equal-power")
    read = design_of(p)
    c = p.tracks[0].clips[0]
    t = np.linspace(c.start, c.start + min(c.duration, design.duration - cut), 2001)
    x = np.clip((c.end - t) / c.fade_out.length, 0.0, 1.0) if c.fade_out.length else 1.0
    expected = np.minimum(1.0, design.amplitude_at(t - at) * gain) * (
        np.sin(0.5 * np.pi * x) if c.fade_out.length else 1.0
    )
    # away from breakpoints, where a step or the envelope's end is a jump and rounding of the
    # shifted time decides the side
    away = np.all(
        np.abs(t[:, None] - (at + np.array([[b[0] for b in design.amplitude]]))) > 1e-6, 1
    )
    assert np.max(np.abs(read.amplitude_at(t) - expected)[away]) <= EDIT_TOLERANCE + 1e-9
    # the emphasis clips are clips of their own: the envelopes' edits leave them as they were
    assert read.emphasis == design.shifted(at).emphasis


def _crossings(x: np.ndarray) -> int:
    return int(np.count_nonzero(np.diff(np.signbit(x[x != 0.0]))))


def test_frequency_breakpoints_are_edited_as_points_and_the_rendered_carrier_follows():
    p = _project()
    tile = p.tracks[0].clips[0].tile_id
    window = slice(int(0.3 * RATE), int(0.45 * RATE))  # amplitude 0.4 there, no emphasis
    assert _crossings(_drive(p)[window]) == pytest.approx(2 * 140.0 * 0.15, abs=2)  # 0.34..0.46
    p, k = tile_shape.add_point(p, tile, 0.5, 0.0, tile_shape.FREQUENCY)
    p = tile_shape.move_point(p, tile, k, 0.5, 1.7, tile_shape.FREQUENCY)  # clamped to 1
    assert design_of(p).frequency == ((0.0, 0.1), (0.5, 1.0), (1.0, 0.9))
    assert design_of(p).amplitude == DESIGN.amplitude  # the other envelope is untouched
    hz = float(np.mean(carrier_hz(0.1 + 0.9 * np.linspace(0.3, 0.45, 1001) / 0.5)))
    assert _crossings(_drive(p)[window]) == pytest.approx(2 * hz * 0.15, abs=2)  # 176..216 Hz
    p = tile_shape.remove_point(p, tile, 0, tile_shape.FREQUENCY)
    assert design_of(p).frequency == ((0.5, 1.0), (1.0, 0.9))
    with pytest.raises(EditError, match="no 'loudness' envelope"):
        tile_shape.move_point(p, tile, 0, 0.5, 0.5, "loudness")
    with pytest.raises(EditError, match="finite"):
        tile_shape.add_point(p, tile, 0.7, float("nan"), tile_shape.FREQUENCY)


def test_a_design_clip_s_emphasis_are_those_on_the_emphasis_track_within_its_span():
    from timeline.edits.vibration import emphasis_of, with_emphasis

    p = _project(at=1.0)  # the design over 1..2 s, its emphasis (both at 1.5 s) below
    design, accents = p.tracks[0].clips[0].id, [c.id for c in p.tracks[1].clips]
    assert emphasis_of(p, design) == accents
    assert with_emphasis(p, [accents[1], design]) == [accents[1], design, accents[0]]
    assert emphasis_of(p, accents[0]) == []  # an emphasis carries nothing
    p = edits.trim_clip(p, design, end=1.4)  # the design now ends before its emphasis
    assert emphasis_of(p, design) == []
    p = _project(at=1.0)
    p = edits.move_track(p, p.tracks[1].id, 0)  # the Emphasis track is no longer below it
    assert emphasis_of(p, p.tracks[1].clips[0].id) == []


point_edits = st.lists(
    st.tuples(
        st.sampled_from(["move", "add", "remove"]),
        st.integers(-1, 6),
        st.floats(-0.5, 1.5) | st.sampled_from([float("nan"), float("inf")]),
        st.floats(-2.0, 2.0) | st.sampled_from([float("nan"), -float("inf")]),
        st.sampled_from(tile_shape.LANES),
    ),
    max_size=12,
)


@settings(max_examples=60, deadline=None)
@given(point_edits)
def test_any_run_of_point_edits_leaves_a_valid_design_or_says_why(steps):
    p = _project()
    tile = p.tracks[0].clips[0].tile_id
    for op, index, t, v, lane in steps:
        before = p.tile(tile).design
        try:
            if op == "move":
                p = tile_shape.move_point(p, tile, index, t, v, lane)
            elif op == "add":
                p, _ = tile_shape.add_point(p, tile, t, v, lane)
            else:
                p = tile_shape.remove_point(p, tile, index, lane)
        except EditError as exc:
            assert str(exc) and p.tile(tile).design == before  # one sentence, nothing lost
            continue
        design = p.tile(tile).design
        other = "frequency" if lane == "amplitude" else "amplitude"
        assert getattr(design, other) == getattr(before, other)
        for points in (design.amplitude, design.frequency):
            times = [q[0] for q in points]
            assert times == sorted(times) and all(0.0 <= x <= design.duration for x in times)
            assert all(0.0 <= q[1] <= 1.0 for q in points)
    x = _drive(p)
    assert np.all(np.isfinite(x)) and np.max(np.abs(x)) <= 2.6 + 1e-9  # envelope 1, pulses 1, 0.6


def test_a_frequency_point_a_denormal_time_after_another_renders_finite_values():
    p = _project()
    tile = p.tracks[0].clips[0].tile_id
    p = tile_shape.move_point(p, tile, 1, 2.225073858507203e-309, 0.0, "frequency")
    x = _drive(p)
    assert np.all(np.isfinite(x)) and abs(x[0]) <= 1e-12  # sin(0) at the knot, not 0 * inf
    assert np.max(np.abs(x)) > 0.1  # the carrier still plays
