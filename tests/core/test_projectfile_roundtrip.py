"""Saving and loading keeps the project's metadata and each track's solo, mute and gain."""

from __future__ import annotations

from timeline import edits
from timeline.files import projectfile


def test_metadata_and_each_tracks_solo_survive_a_reload(tmp_path) -> None:
    project = edits.new_project(templates=False, title="Knob", author="A. Designer")
    project, first = edits.add_track(project, "drive")
    project, second = edits.add_track(project, "damping")
    project, third = edits.add_track(project, "drive")
    project = edits.set_track(project, first, solo=True)
    project = edits.set_track(project, third, solo=True, mute=True, gain=0.5)
    path = tmp_path / "p.htl"
    projectfile.save(project, path)
    loaded = projectfile.load(path)
    assert dict(loaded.metadata) == {"title": "Knob", "author": "A. Designer"}
    assert [(t.id, t.solo, t.mute, t.gain) for t in loaded.tracks] == [
        (first, True, False, 1.0),
        (second, False, False, 1.0),
        (third, True, True, 0.5),
    ]
    assert loaded == project
