"""A video editor's OTIO timeline imports as context: its sound on audio tracks, its markers and
cuts as markers, all at their times in the edit (built here the way Premiere's export is laid
out: a picture track, audio tracks, media starting at a timecode, markers on the stack)."""

from __future__ import annotations

import numpy as np
import opentimelineio as otio
import pytest
import soundfile as sf

from importers.otio import _read
from importers.otio_context import read_context
from timeline import edits
from timeline.files import importing
from timeline.plugins.file_formats import FormatError

RT, TR = otio.opentime.RationalTime, otio.opentime.TimeRange
HOUR = 86400  # 01:00:00:00 at 24 fps: where the editor's media timecode starts


def _edit(folder):
    """A cut: picture, a dialogue track (one clip plain, one in a nested stack naming its medium
    by the editor's path) and a music track whose medium is on the editor's machine only."""
    rate = 8000
    (folder / "media").mkdir()
    sf.write(folder / "media" / "door.wav", np.arange(2 * rate) / (2.0 * rate), rate, "FLOAT")
    timeline = otio.schema.Timeline("sc01")
    timeline.tracks.markers.append(otio.schema.Marker("Slam", TR(RT(60, 30), RT(0, 30))))
    timeline.tracks.markers.append(otio.schema.Marker("", TR(RT(90, 30), RT(0, 30))))  # RED
    picture = otio.schema.Track("V1", kind="Video")
    picture.append(otio.schema.Gap(duration=RT(12, 24)))
    picture.append(otio.schema.Clip("sh010.mov", source_range=TR(RT(0, 15), RT(30, 15))))
    door = otio.schema.ExternalReference("media/door.wav", TR(RT(HOUR, 24), RT(48, 24)))
    dialogue = otio.schema.Track("Dialogue", kind="Audio")
    dialogue.append(otio.schema.Gap(duration=RT(24, 24)))
    clip = otio.schema.Clip("door", door, TR(RT(HOUR + 12, 24), RT(24, 24)))
    clip.markers.append(otio.schema.Marker("latch", TR(RT(HOUR + 18, 24), RT(0, 24))))
    dialogue.append(clip)
    nested = otio.schema.Stack("nest")
    inner = otio.schema.Track("inner", kind="Audio")
    inner.append(otio.schema.Gap(duration=RT(12, 24)))
    editors = "file://localhost/D%3a/media/door.wav"  # found by name in the .otio's media/
    again = otio.schema.ExternalReference(editors, TR(RT(HOUR, 24), RT(48, 24)))
    inner.append(otio.schema.Clip("door again", again, TR(RT(HOUR, 24), RT(12, 24))))
    nested.append(inner)
    dialogue.append(nested)
    music = otio.schema.Track("Music", kind="Audio")
    elsewhere = otio.schema.ExternalReference("file://localhost/D%3a/media/score.wav")
    music.append(otio.schema.Clip("score", elsewhere, TR(RT(0, 24), RT(72, 24))))
    timeline.tracks.extend([picture, dialogue, music])
    path = folder / "cut" / "sc01.otio"
    path.parent.mkdir()
    otio.adapters.write_to_file(timeline, str(path))
    (path.parent / "media").symlink_to(folder / "media")  # relative to the .otio's folder
    return path


def test_a_cut_imports_as_sound_and_markers_aligned(tmp_path, monkeypatch):
    path = _edit(tmp_path)
    monkeypatch.chdir(tmp_path)  # relative media resolve against the .otio, not here
    imported = _read(path)
    notes = imported.notes
    project, _ = importing.place(edits.new_project(templates=False), imported)
    assert [(t.name, t.kind, t.mute) for t in project.tracks] == [
        ("Dialogue", "audio", False),
        ("Music", "audio", False),
    ]
    door, again = project.tracks[0].clips
    assert (door.start, door.source_in, door.source_out) == (1.0, 0.5, 1.5)
    # the nested stack starts after the door clip (2.0 s), its clip half a second into it
    assert (again.start, again.source_in, again.source_out) == (2.5, 0.0, 0.5)
    assert door.tile_id == again.tile_id  # one medium, read once
    sound = project.tile(door.tile_id)
    assert sound.rate == 8000 and sound.data[4000] == pytest.approx(0.25)  # 0.5 s in
    (score,) = project.tracks[1].clips
    assert (score.start, score.duration) == (0.0, 3.0)
    assert project.tile(score.tile_id).name == "score"  # silent, its span kept
    assert notes == (
        "1 audio clip(s) placed silent: their media were not found or are not sound files "
        "(score.wav)",
        "1 picture cut(s) placed as markers named after their shots",
    )
    assert [(m.at, m.name) for m in project.markers] == [
        (0.5, "sh010.mov"),  # the shot's cut
        (1.25, "latch"),  # a clip's marker, a quarter second into the door clip
        (2.0, "Slam"),
        (3.0, "red"),  # an unnamed marker goes by its colour
    ]


def test_a_timeline_with_nothing_to_design_against_is_refused(tmp_path):
    picture = otio.schema.Track("V1", kind="Video")
    picture.append(otio.schema.Gap(duration=RT(24, 24)))
    timeline = otio.schema.Timeline("empty")
    timeline.tracks.append(picture)
    with pytest.raises(FormatError, match="e.otio was not written by haptic-timeline and holds no"):
        read_context(timeline, tmp_path / "e.otio")


def test_a_picture_only_cut_in_a_collection_imports_its_cuts(tmp_path):
    """Most of OTIO's sample timelines are picture only (clips with MissingReferences)."""
    picture = otio.schema.Track("Sequence", kind="Video")
    for name, frames in (("tech.mp4", 720), ("out-b.mp4", 722)):
        picture.append(
            otio.schema.Clip(name, otio.schema.MissingReference(), TR(RT(0, 24), RT(frames, 24)))
        )
        picture.append(otio.schema.Gap(duration=RT(84, 24)))
    timeline = otio.schema.Timeline("NestedScope")
    timeline.tracks.append(picture)
    collection = otio.schema.SerializableCollection("reel", [timeline])
    otio.adapters.write_to_file(collection, str(tmp_path / "reel.otio"))
    imported = _read(tmp_path / "reel.otio")
    assert imported.placements == ()
    assert imported.markers == (("tech.mp4", 0.0), ("out-b.mp4", 33.5))  # 720 + 84 frames
