"""AHAP, .haptic and OTIO: reading real files, and write -> read within stated tolerances."""

from __future__ import annotations

import json

import numpy as np
import pytest

from importers import _vibration as vib
from timeline import edits, exporting, importing
from timeline.formats import FormatError
from timeline.model import Fade
from timeline.tiles import SampledTile, generator

ENVELOPE_TOLERANCE = 0.03  # amplitude, away from the envelope's first and last 5 ms
EDGE = 0.005


def _envelope(doc: dict) -> tuple[np.ndarray, np.ndarray, list]:
    amp = doc["signals"]["continuous"]["envelopes"]["amplitude"]
    t = np.array([b["time"] for b in amp])
    v = np.array([b["amplitude"] for b in amp])
    emphasis = [(b["time"], b["emphasis"]) for b in amp if "emphasis" in b]
    return t, v, emphasis


def _design() -> dict:
    return {
        "version": {"major": 1, "minor": 0, "patch": 0},
        "signals": {
            "continuous": {
                "envelopes": {
                    "amplitude": [
                        {"time": 0.0, "amplitude": 0.1},
                        {
                            "time": 0.1,
                            "amplitude": 0.6,
                            "emphasis": {"amplitude": 0.9, "frequency": 0.3},
                        },
                        {"time": 0.25, "amplitude": 0.3},
                        {"time": 0.4, "amplitude": 0.8},
                        {"time": 0.5, "amplitude": 0.2},
                    ],
                    "frequency": [
                        {"time": 0.0, "frequency": 0.2},
                        {"time": 0.3, "frequency": 0.9},
                        {"time": 0.5, "frequency": 0.5},
                    ],
                }
            }
        },
    }


def test_haptic_write_read_keeps_breakpoints_and_emphasis(tmp_path):
    src = tmp_path / "in.haptic"
    src.write_text(json.dumps(_design()))
    project, _ = importing.import_file(edits.new_project(), src)
    exporting.export_project(project, tmp_path / "out.haptic")
    t0, v0, e0 = _envelope(_design())
    t1, v1, e1 = _envelope(json.loads((tmp_path / "out.haptic").read_text()))
    inner = (t0 > t0[0] + EDGE) & (t0 < t0[-1] - EDGE)
    assert np.abs(np.interp(t0, t1, v1) - v0)[inner].max() < ENVELOPE_TOLERANCE
    grid = np.linspace(t0[0] + EDGE, t0[-1] - EDGE, 1000)
    assert np.abs(np.interp(grid, t1, v1) - np.interp(grid, t0, v0)).max() < ENVELOPE_TOLERANCE
    assert abs(t1[0] - t0[0]) <= 0.001 and abs(t1[-1] - t0[-1]) <= 0.001
    assert e1 == e0  # emphasis: time and values kept exactly


def test_ahap_write_read_keeps_events_and_curves(tmp_path):
    src = tmp_path / "in.haptic"
    src.write_text(json.dumps(_design()))
    project, _ = importing.import_file(edits.new_project(), src)
    exporting.export_project(project, tmp_path / "out.ahap")
    doc = json.loads((tmp_path / "out.ahap").read_text())
    events = [p["Event"] for p in doc["Pattern"] if "Event" in p]
    transients = [e for e in events if e["EventType"] == "HapticTransient"]
    continuous = [e for e in events if e["EventType"] == "HapticContinuous"]
    assert [e["Time"] for e in transients] == [0.1]
    assert transients[0]["EventParameters"][0]["ParameterValue"] == pytest.approx(0.9**0.5, 1e-6)
    assert abs(continuous[0]["Time"]) <= 0.001
    assert abs(continuous[0]["Time"] + continuous[0]["EventDuration"] - 0.5) <= 0.001
    for p in doc["Pattern"]:
        if "ParameterCurve" in p:
            assert len(p["ParameterCurve"]["ParameterCurveControlPoints"]) <= 16
    back, _ = importing.import_file(edits.new_project(), tmp_path / "out.ahap")
    original_clips = sorted((c.start, c.duration) for c in project.tracks[0].clips)
    back_clips = sorted((c.start, c.duration) for c in back.tracks[0].clips)
    assert len(back_clips) == len(original_clips)
    for (s0, d0), (s1, d1) in zip(original_clips, back_clips, strict=True):
        assert abs(s0 - s1) <= 0.001 and abs(d0 - d1) <= 0.002


def test_long_continuous_events_are_split_at_30_seconds(tmp_path):
    project = edits.new_project(rate=2000.0)
    project, track = edits.add_track(project, "drive")
    t = np.arange(int(70 * 2000)) / 2000
    project, tile = edits.add_tile(project, SampledTile(0.5 * np.sin(2 * np.pi * 155 * t), 2000))
    project, _ = edits.add_clip(project, track, tile, 0.0)
    exporting.export_project(project, tmp_path / "long.ahap")
    doc = json.loads((tmp_path / "long.ahap").read_text())
    spans = [
        (e["Event"]["Time"], e["Event"]["EventDuration"]) for e in doc["Pattern"] if "Event" in e
    ]
    assert [d for _, d in spans[:2]] == [30.0, 30.0]
    assert spans[2][1] == pytest.approx(10.0, abs=0.001)  # ends at the last sample
    curves = [p["ParameterCurve"] for p in doc["Pattern"] if "ParameterCurve" in p]
    intensity = [c for c in curves if c["ParameterID"] == "HapticIntensityControl"]
    values = [p["ParameterValue"] for c in intensity for p in c["ParameterCurveControlPoints"]]
    assert max(abs(v - 0.5**0.5) for v in values[1:-1]) < 0.02  # intensity = sqrt(amplitude)


def test_transient_clip_exports_as_a_transient(tmp_path):
    project = edits.new_project()
    project, track = edits.add_track(project, "drive")
    placement = vib.transient_placement(0.123, 0.64, 0.5)
    project, tile = edits.add_tile(project, placement.tile)
    project, _ = edits.add_clip(project, track, tile, 0.123, **placement.clip)
    exporting.export_project(project, tmp_path / "t.ahap")
    events = [p["Event"] for p in json.loads((tmp_path / "t.ahap").read_text())["Pattern"]]
    assert events == [
        {
            "Time": 0.123,
            "EventType": "HapticTransient",
            "EventParameters": [
                {"ParameterID": "HapticIntensity", "ParameterValue": 0.8},
                {"ParameterID": "HapticSharpness", "ParameterValue": 0.5},
            ],
        }
    ]


def test_otio_round_trip_keeps_clips_exactly(tmp_path):
    project = edits.new_project()
    project, drive = edits.add_track(project, "drive", "Buzz")
    project, stiff = edits.add_track(project, "stiffness", gain=0.5, mute=True)
    project, sine = edits.add_tile(project, generator("sine", 0.3, frequency=20))
    project, rec = edits.add_tile(project, SampledTile(np.linspace(-1, 1, 777), 1234.5, "rec"))
    project, _ = edits.add_clip(project, drive, sine, 0.1, gain=0.7, fade_in=Fade(0.05, "s-curve"))
    project, _ = edits.add_clip(
        project, drive, rec, 0.2, reverse=True, source_in=0.1, source_out=0.5
    )  # overlaps the first: a second OTIO lane
    project, _ = edits.add_clip(project, stiff, sine, 1 / 3, stretch=2.5, stretch_mode="repeat")
    exporting.export_project(project, tmp_path / "p.otio")
    back, _ = importing.import_file(edits.new_project(), tmp_path / "p.otio")
    assert [(t.kind, t.name, t.gain, t.mute) for t in back.tracks] == [
        (t.kind, t.name, t.gain, t.mute) for t in project.tracks
    ]
    for before, after in zip(project.tracks, back.tracks, strict=True):
        assert len(before.clips) == len(after.clips)
        for c0, c1 in zip(before.clips, after.clips, strict=True):
            assert (c0.start, c0.duration) == (c1.start, c1.duration)
            fields = (
                "source_in",
                "source_out",
                "stretch",
                "stretch_mode",
                "gain",
                "reverse",
                "fade_in",
                "fade_out",
            )
            assert all(getattr(c0, f) == getattr(c1, f) for f in fields)
            assert project.tile(c0.tile_id) == back.tile(c1.tile_id)


def test_foreign_otio_is_refused(tmp_path):
    import opentimelineio as otio

    otio.adapters.write_to_file(otio.schema.Timeline(name="film"), str(tmp_path / "f.otio"))
    with pytest.raises(FormatError, match="not written by haptic-timeline"):
        importing.read_file(tmp_path / "f.otio")


# --- the corpus of real files ------------------------------------------------------------------

REJECTED = {
    "invalid_fields_v1.haptic": "no signals",
    "invalid_version_v1.haptic": "version 2",
    "validation_v1_amplitude.haptic": "between 0 and 1",
    "validation_v1_emphasis_amplitude_range.haptic": "between 0 and 1",
    "validation_v1_emphasis_frequency_range.haptic": "between 0 and 1",
    "validation_v1_sequence.haptic": "goes back in time",
    "player_one_amp_bp.haptic": "no haptic events",
    "player_one_amp_bp_multiple_freq_bps.haptic": "no haptic events",
    "truncate_before_1_bp.haptic": "no haptic events",
    "invalid_fields.ahap": "not an Event",
}


def test_corpus_files_import_or_are_rejected_as_expected(corpus):
    files = sorted(corpus.glob("*/*.haptic")) + sorted(corpus.glob("*/*.ahap"))
    assert files
    for path in files:
        if path.name in REJECTED:
            with pytest.raises(FormatError, match=REJECTED[path.name]):
                importing.read_file(path)
        else:
            imported = importing.read_file(path)
            assert imported.placements, path.name


def test_converted_pairs_agree(corpus):
    """Lofelt's converter made each .ahap from a .haptic: both read to the same waveform."""
    for name in ("3_points", "16_points", "17_points", "long_clip"):
        a = importing.read_file(corpus / "ahap" / f"{name}.ahap").placements
        h = importing.read_file(corpus / "ahap" / f"{name}.haptic").placements
        assert [p.start for p in a] == [p.start for p in h]
        n = min(len(a[0].tile.data), len(h[0].tile.data))
        # The converter interpolates sqrt(amplitude) between breakpoints, so the squared curve
        # sags below the straight one by at most a quarter of the largest step.
        _, levels, _ = _envelope(json.loads((corpus / "ahap" / f"{name}.haptic").read_text()))
        bound = np.abs(np.diff(levels)).max() / 4 + 1e-3
        assert np.abs(a[0].tile.data[:n] - h[0].tile.data[:n]).max() < bound


def test_corpus_haptic_write_read(corpus, tmp_path):
    """Real designs survive export within tolerance where envelopes are not sub-millisecond."""
    for name in ("player_normal_with_2_emphasis", "valid_v1", "player_ramp_up_with_emp"):
        src = corpus / "haptic" / f"{name}.haptic"
        project, _ = importing.import_file(edits.new_project(), src)
        exporting.export_project(project, tmp_path / "out.haptic")
        t0, v0, e0 = _envelope(json.loads(src.read_text()))
        t1, v1, e1 = _envelope(json.loads((tmp_path / "out.haptic").read_text()))
        grid = np.linspace(t0[0] + EDGE, t0[-1] - EDGE, 2000)
        err = np.abs(np.interp(grid, t1, v1) - np.interp(grid, t0, v0))
        assert err.max() < ENVELOPE_TOLERANCE, name
        assert [t for t, _ in e1] == [t for t, _ in e0]


def test_corpus_recordings_import(corpus):
    for wav in sorted((corpus / "audio-pairs").glob("*.wav")):
        tile = importing.read_file(wav).placements[0].tile
        assert tile.rate > 0 and len(tile.data) > 100 and np.abs(tile.data).max() <= 1.0
