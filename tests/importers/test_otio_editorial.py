"""An exported .otio converts through OTIO's own editorial adapters at a video rate, and an .otioz
bundle carries every medium."""

from __future__ import annotations

import opentimelineio as otio
import pytest

from importers.otio import _read
from timeline import edits
from timeline.errors import FormatError
from timeline.files import exporting, importing
from timeline.tiles import generator


def _project():
    """Drive clips from 0.1 to 0.6 s and from 0.7 to 0.71 s (under half a frame), a stiffness
    clip from 0.25 to 0.45 s."""
    p = edits.new_project(templates=False, title="Knock")
    p, drive = edits.add_track(p, "drive", "Buzz")
    p, sine = edits.add_tile(p, generator("sine", 0.5))
    p, _ = edits.add_clip(p, drive, sine, 0.1)
    p, tick = edits.add_tile(p, generator("square", 0.01))
    p, _ = edits.add_clip(p, drive, tick, 0.7)
    p, spring = edits.add_track(p, "stiffness", "Spring")
    p, ramp = edits.add_tile(p, generator("ramp", 0.2))
    p, _ = edits.add_clip(p, spring, ramp, 0.25)
    return p


def _spans(timeline):
    """(name, start frame, frames) of each audio clip, in track order."""
    return [
        (c.name, c.range_in_parent().start_time.value, c.duration().value)
        for t in timeline.tracks
        if t.kind == "Audio"
        for c in t.find_clips()
    ]


@pytest.mark.parametrize(
    ("adapter", "package", "rate"),
    [
        ("fcp_xml", "otio_fcp_adapter", 24),
        ("fcp_xml", "otio_fcp_adapter", 23.976),
        ("fcpx_xml", "otio_fcpx_xml_adapter", 24),
    ],
)
def test_a_video_rate_export_converts_through_otio_adapters(tmp_path, adapter, package, rate):
    pytest.importorskip(package)
    out = tmp_path / "knock.otio"
    exporting.export_project(_project(), out, rate=rate)
    timeline = otio.adapters.read_from_file(str(out))
    converted = otio.adapters.read_from_string(
        otio.adapters.write_to_string(timeline, adapter), adapter
    )
    frames = round(rate)  # 23.976 counts 24 frames a (slightly long) second
    first, second = round(0.1 * frames), round(0.25 * frames)
    tick = round(0.7 * frames)
    assert _spans(converted) == [
        ("sine", first, round(0.6 * frames) - first),
        ("square", tick, round(0.71 * frames) - tick),  # 0 frames, still on the picture track
        ("ramp", second, round(0.45 * frames) - second),
    ]
    # our own fields ride along unrounded: the .otio still reads back exactly
    back = [
        (p.start, p.start + p.clip["source_out"] - p.clip["source_in"])
        for p in _read(out).placements
    ]
    assert back == [(0.1, 0.6), (0.7, 0.71), (0.25, 0.45)]


def test_a_rate_with_no_timecode_is_refused_before_writing(tmp_path):
    out = tmp_path / "knock.otio"
    with pytest.raises(FormatError, match="10000 is not a timecode rate"):
        exporting.export_project(_project(), out, rate=10_000)
    assert list(tmp_path.iterdir()) == []


def test_a_bundle_carries_every_medium(tmp_path):
    out = tmp_path / "knock.otioz"
    exporting.export_project(_project(), out)
    unpacked = tmp_path / "unpacked"
    unpacked.mkdir()
    timeline = otio.adapters.read_from_file(str(out), extract_to_directory=str(unpacked))
    urls = sorted(
        {r.target_url for c in timeline.find_clips() for r in c.media_references().values()}
    )
    assert urls == ["media/knock-Buzz.haptic", "media/knock-Buzz.wav", "media/knock-Spring.wav"]
    assert all((unpacked / url).stat().st_size > 0 for url in urls)
    drive, _ = importing.import_file(
        edits.new_project(templates=False), unpacked / "media/knock-Buzz.haptic"
    )
    assert drive.duration == pytest.approx(0.71, abs=1e-3)  # the drive, as .haptic
    back, _ = importing.import_file(edits.new_project(templates=False), out)
    ends = [(c.start, c.end) for t in back.tracks for c in t.clips]
    assert ends == [(0.1, 0.6), (0.7, 0.71), (0.25, 0.45)]
    assert not any(p.name.startswith(".") for p in tmp_path.iterdir())  # no temporaries left
