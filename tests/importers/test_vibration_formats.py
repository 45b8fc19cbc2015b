""".haptic and AHAP: designs kept as envelopes, exact and bounded round trips, validity, notes."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from importers import ahap
from importers.ahap_playback import playback
from timeline import edits
from timeline.edits.vibration import Emphasis, VibrationDesign, design_of, place_design
from timeline.files import importing
from timeline.plugins.file_formats import FormatError
from timeline.tiles import generator

from .vibration_checks import (
    check_ahap_round_trip,
    check_envelopes_kept_through_ahap,
    check_written_back_exactly,
)
from .vibration_checks import export_doc as _export
from .vibration_checks import player as _player
from .vibration_checks import read_project as _read

REJECTED = {
    "invalid_fields_v1.haptic": "no signals",
    "invalid_version_v1.haptic": "version 2",
    "validation_v1_amplitude.haptic": "between 0 and 1",
    "validation_v1_emphasis_amplitude_range.haptic": "between 0 and 1",
    "validation_v1_emphasis_frequency_range.haptic": "between 0 and 1",
    "validation_v1_sequence.haptic": "goes back in time",
    "player_one_amp_bp.haptic": "has one breakpoint; it needs at least two",
    "player_one_amp_bp_multiple_freq_bps.haptic": "has one breakpoint; it needs at least two",
    "truncate_before_1_bp.haptic": "has one breakpoint; it needs at least two",
    "invalid_fields.ahap": "not an Event",
}


def _haptic_doc(amplitude, frequency=None) -> dict:
    envelopes: dict = {"amplitude": amplitude}
    if frequency is not None:
        envelopes["frequency"] = frequency
    return {
        "version": {"major": 1, "minor": 0},
        "signals": {"continuous": {"envelopes": envelopes}},
    }


def _write(tmp_path: Path, name: str, doc: dict) -> Path:
    path = tmp_path / name
    path.write_text(json.dumps(doc))
    return path


def _valid(corpus: Path, pattern: str) -> list[Path]:
    return [p for p in sorted(corpus.glob(pattern)) if p.name not in REJECTED]


# --- the corpus ---------------------------------------------------------------------------------


def test_corpus_files_import_or_are_rejected_with_the_reason(corpus):
    files = sorted(corpus.glob("*/*.haptic")) + sorted(corpus.glob("*/*.ahap"))
    assert len(files) > 60
    for path in files:
        if path.name in REJECTED:
            with pytest.raises(FormatError, match=REJECTED[path.name]):
                importing.read_file(path)
        else:
            assert importing.read_file(path).placements, path.name


def test_an_unedited_haptic_is_written_back_exactly(corpus, tmp_path):
    files = _valid(corpus, "*/*.haptic")
    assert len(files) > 50
    for path in files:
        check_written_back_exactly(path, tmp_path)


def test_haptic_to_ahap_and_back_keeps_the_envelopes(corpus, tmp_path):
    for path in _valid(corpus, "*/*.haptic"):
        check_envelopes_kept_through_ahap(path, tmp_path)


def test_meta_made_ahap_round_trips_within_the_bound(corpus, tmp_path):
    for path in _valid(corpus, "ahap/*.ahap"):
        check_ahap_round_trip(path, tmp_path)


def test_meta_converter_sharpness_and_ducking_are_read_back(corpus):
    # long_clip: Meta's converter wrote intensity sqrt(0.5) * 0.8 at the emphasis at 5 s.
    design = design_of(_read(corpus / "ahap" / "long_clip.ahap"))
    source = design_of(_read(corpus / "ahap" / "long_clip.haptic"))
    assert design.amplitude_at(np.array([5.0]))[0] == pytest.approx(0.5, abs=1e-6)
    assert [(e.time, e.frequency) for e in design.emphasis] == [(5.0, 1.0)]
    assert design.emphasis[0].amplitude == pytest.approx(0.75, abs=1e-7)
    assert source.emphasis[0].time == 5.0
    # sharpness = sqrt(frequency) between 0 and 1 at 0 s and 10 s: frequency is its square
    assert design.frequency_at(np.array([5.0]))[0] == pytest.approx(0.25, abs=0.005)


# --- conventions, emphasis, joins, silence ------------------------------------------------------


def _design_project(design: VibrationDesign):
    return place_design(edits.new_project(templates=False), design)


def _pattern(doc: dict, kind: str) -> list[dict]:
    return [p[kind] for p in doc["Pattern"] if kind in p]


def test_ahap_intensity_is_fitted_where_the_player_interpolates(tmp_path):
    ramp = VibrationDesign(((0.0, 0.0), (2.0, 1.0)), ((0.0, 0.25), (2.0, 0.25)), (), 2.0)
    out = tmp_path / "ramp.ahap"
    _export(_design_project(ramp), out)
    curves, _, _ = _player(out)
    t = np.linspace(0.0, 2.0, 2001)
    heard = curves["HapticIntensityControl"].at(t) ** 2
    assert (
        np.max(np.abs(heard - t / 2)) <= ahap.WRITE_TOLERANCE + 1e-12
    )  # a straight sqrt fit was 0.25 low mid-ramp
    # Meta's convention: sharpness = sqrt(frequency)
    assert curves["HapticSharpnessControl"].at(np.array([1.0]))[0] == pytest.approx(0.5)


def test_an_emphasis_plays_at_its_own_intensity_over_an_unducked_envelope(tmp_path):
    """Controls scale transients too (Apple): at the emphasis a continuous event restarts at the
    envelope's intensity so the control is 1 there; no ducking is added (issue 23)."""
    design = VibrationDesign(
        ((0.0, 0.25), (0.1, 0.25), (0.2, 0.25)), ((0.0, 0.5),), (Emphasis(0.1, 0.64, 0.3),), 0.2
    )
    doc = _export(_design_project(design), tmp_path / "e.ahap")
    played = playback(doc)
    assert played.transients == [(0.1, 0.8, 0.3)]
    level, _ = played.continuous_at(np.array([0.05, 0.1, 0.15]))
    assert np.allclose(level**2, 0.25, rtol=0, atol=1e-12)
    assert design_of(_read(tmp_path / "e.ahap")).amplitude_at(np.array([0.1]))[0] == pytest.approx(
        0.25
    )


def test_apple_style_ahap_reads_sharpness_as_frequency(tmp_path):
    doc = {
        "Version": 1.0,
        "Pattern": [
            {
                "Event": {
                    "Time": 0.0,
                    "EventType": "HapticContinuous",
                    "EventDuration": 0.5,
                    "EventParameters": [
                        {"ParameterID": "HapticIntensity", "ParameterValue": 0.6},
                        {"ParameterID": "HapticSharpness", "ParameterValue": 0.3},
                    ],
                }
            }
        ],
    }
    path = _write(tmp_path, "apple.ahap", doc)
    design = design_of(_read(path))
    assert design.amplitude_at(np.array([0.25]))[0] == pytest.approx(0.36)
    assert design.frequency_at(np.array([0.25]))[0] == pytest.approx(0.3)
    out = _export(_read(path), tmp_path / "again.ahap")
    assert out["Metadata"]["Description"] == ahap.LINEAR_NOTE
    assert design_of(_read(tmp_path / "again.ahap")).frequency_at(np.array([0.25]))[
        0
    ] == pytest.approx(0.3)


def test_two_emphases_at_one_time_both_survive_haptic(tmp_path):
    design = VibrationDesign(
        ((0.0, 0.2), (0.3, 0.2)),
        ((0.0, 0.5),),
        (Emphasis(0.1, 0.9, 0.2), Emphasis(0.1, 0.5, 0.8)),
        0.3,
    )
    doc = _export(_design_project(design), tmp_path / "two.haptic")
    amp = doc["signals"]["continuous"]["envelopes"]["amplitude"]
    assert [b["time"] for b in amp] == [0.0, 0.1, 0.1, 0.3]
    assert [b["emphasis"] for b in amp if "emphasis" in b] == [
        {"amplitude": 0.9, "frequency": 0.2},
        {"amplitude": 0.5, "frequency": 0.8},
    ]
    assert design_of(_read(tmp_path / "two.haptic")).emphasis == design.emphasis


def test_joined_continuous_events_do_not_add_at_the_join(tmp_path):
    def event(time, duration, intensity):
        return {
            "Event": {
                "Time": time,
                "EventType": "HapticContinuous",
                "EventDuration": duration,
                "EventParameters": [
                    {"ParameterID": "HapticIntensity", "ParameterValue": intensity}
                ],
            }
        }

    path = _write(tmp_path, "j.ahap", {"Pattern": [event(0.0, 0.5, 0.5), event(0.5, 0.5, 0.7)]})
    design = design_of(_read(path))
    assert np.allclose(design.amplitude, [(0.0, 0.25), (0.5, 0.25), (0.5, 0.49), (1.0, 0.49)])
    assert design.amplitude_at(np.array([0.5]))[0] == pytest.approx(0.49)  # not 0.25 + 0.49


def test_a_silent_design_exports_to_both_formats(tmp_path):
    silent = VibrationDesign(((0.0, 0.0), (1.0, 0.0)), ((0.0, 0.1), (1.0, 0.9)), (), 1.0)
    project = _design_project(silent)
    haptic = _export(project, tmp_path / "s.haptic")["signals"]["continuous"]["envelopes"]
    assert haptic["frequency"] == [{"time": 0.0, "frequency": 0.1}, {"time": 1.0, "frequency": 0.9}]
    _export(project, tmp_path / "s.ahap")
    back = design_of(_read(tmp_path / "s.ahap"))
    assert max(v for _, v in back.amplitude) == 0.0
    assert back.frequency_at(np.array([0.5]))[0] == pytest.approx(0.5, abs=0.01)


def test_a_short_sine_clip_exports_as_a_transient(tmp_path):
    project, track = edits.add_track(edits.new_project(templates=False), "drive")
    project, tile = edits.add_tile(project, generator("sine", 0.01, frequency=155.0))
    project, _ = edits.add_clip(project, track, tile, 0.123, gain=0.64)
    events = _pattern(_export(project, tmp_path / "t.ahap"), "Event")
    transients = [e for e in events if e["EventType"] == "HapticTransient"]
    assert len(transients) == 1 and transients[0]["Time"] == 0.123
    assert [p["ParameterValue"] for p in transients[0]["EventParameters"]] == [0.8, 0.5]


def test_long_designs_split_into_30_second_continuous_events(tmp_path):
    design = VibrationDesign(((0.0, 0.5), (70.0, 0.5)), ((0.0, 0.5),), (), 70.0)
    events = _pattern(_export(_design_project(design), tmp_path / "l.ahap"), "Event")
    assert [(e["Time"], e["EventDuration"]) for e in events] == [(0, 30), (30, 30), (60, 10)]
    for curve in _pattern(_export(_design_project(design), tmp_path / "l.ahap"), "ParameterCurve"):
        assert len(curve["ParameterCurveControlPoints"]) <= ahap.MAX_CURVE_POINTS


def test_an_edited_design_is_written_from_its_edited_breakpoints(corpus, tmp_path):
    project = _read(corpus / "haptic" / "valid_v1.haptic")
    clip = project.tracks[0].clips[0].id
    source = json.loads((corpus / "haptic" / "valid_v1.haptic").read_text())
    doc = _export(edits.set_clip_gain(project, clip, 0.5), tmp_path / "half.haptic")
    amp0 = source["signals"]["continuous"]["envelopes"]["amplitude"]
    amp1 = doc["signals"]["continuous"]["envelopes"]["amplitude"]
    assert [b["amplitude"] for b in amp1] == [b["amplitude"] * 0.5 for b in amp0]


# --- validity and notes -------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("amplitude", "message"),
    [
        ([{"time": 0.2, "amplitude": 0.5}, {"time": 0.2, "amplitude": 0.7}], "lasts zero seconds"),
        ([{"time": 0.0, "amplitude": 0.5}], "has one breakpoint; it needs at least two"),
        ([], "is empty; it needs at least two"),
        (
            [{"time": 0.0, "amplitude": 0.5}, {"time": 0.1}],
            "amplitude breakpoint 2 has no amplitude",
        ),
        (
            [{"time": 0.0, "amplitude": 0.5}, {"amplitude": 0.1}],
            "amplitude breakpoint 2 has no time",
        ),
    ],
)
def test_invalid_haptic_files_say_what_is_wrong(tmp_path, amplitude, message):
    path = _write(tmp_path, "bad.haptic", _haptic_doc(amplitude))
    with pytest.raises(FormatError, match=message):
        importing.read_file(path)


def test_a_missing_amplitude_envelope_is_reported_as_missing(tmp_path):
    doc = _haptic_doc([])
    del doc["signals"]["continuous"]["envelopes"]["amplitude"]
    with pytest.raises(FormatError, match="has no amplitude envelope"):
        importing.read_file(_write(tmp_path, "none.haptic", doc))


def test_notes_say_what_was_assumed_or_will_change(tmp_path):
    amplitude = [
        {"time": 0.0, "amplitude": 0.5, "emphasis": {"amplitude": 0.2, "frequency": 0.5}},
        {"time": 0.4, "amplitude": 0.5},
    ]
    notes = importing.read_file(_write(tmp_path, "n.haptic", _haptic_doc(amplitude))).notes
    assert any("no frequency envelope" in n for n in notes)
    assert any("weaker than its breakpoint" in n for n in notes)
    clamped = {
        "Pattern": [
            {
                "Event": {
                    "Time": 0.0,
                    "EventType": "HapticTransient",
                    "EventParameters": [{"ParameterID": "HapticIntensity", "ParameterValue": 1.5}],
                }
            }
        ]
    }
    notes = importing.read_file(_write(tmp_path, "c.ahap", clamped)).notes
    assert any("clamped to 1" in n for n in notes)


def test_an_ahap_without_events_says_so(tmp_path):
    path = _write(tmp_path, "e.ahap", {"Pattern": []})
    with pytest.raises(FormatError, match="holds no haptic events"):
        importing.read_file(path)
    assert math.isfinite(ahap.MAX_EVENTS)


def test_ahap_fuzz_finds_are_one_sentence(tmp_path):
    """Found by the reliability fuzzer: a zero-length-only pattern and an integer beyond float."""
    only_zero = {
        "Pattern": [{"Event": {"Time": 0.0, "EventType": "HapticContinuous", "EventDuration": 0.0}}]
    }
    huge = {
        "Pattern": [
            {"Event": {"Time": 10**400, "EventType": "HapticTransient", "EventParameters": []}}
        ]
    }
    for name, doc, says in (
        ("zero.ahap", only_zero, "holds no haptic events that last"),
        ("huge.ahap", huge, "is too large"),
    ):
        path = tmp_path / name
        path.write_text(json.dumps(doc))
        with pytest.raises(FormatError, match=says):
            importing.read_file(path)
