"""The source sound heard with the haptics: what the card is fed, and no card is one sentence."""

from __future__ import annotations

import threading

import numpy as np

from timeline import edits
from timeline.edits.sound_track import add_sound
from timeline.rendering.sound_out import SoundOut
from timeline.rendering.source_sound import render_sound

RATE = 8000.0


def sound_project():
    p = edits.new_project(templates=False)
    sound = 0.5 * np.sin(2 * np.pi * 300 * np.arange(8000) / RATE)
    p, _ = add_sound(p, sound, RATE, name="tone")
    return p, p.tracks[-1].id


def pull(out: SoundOut, frames: int, block: int = 512) -> np.ndarray:
    got = []
    for _ in range(frames // block):
        buf = np.empty((block, 1), np.float32)
        out._callback(buf, block, None, None)
        got.append(buf[:, 0].copy())
    return np.concatenate(got)


def test_the_card_gets_the_context_tracks_and_follows_gain_edits() -> None:
    project, track = sound_project()
    out = SoundOut()
    out.project = project
    feeder = threading.Thread(target=out._feed, args=(0.0, 1.0, RATE, True), daemon=True)
    feeder.start()  # looping: it renders until stopped, a second (4 chunks) ahead of the card
    feeder.join(0.5)
    first = pull(out, 2048)
    np.testing.assert_allclose(first, render_sound(project, 0.0, 2048 / RATE, RATE), atol=1e-6)
    out.follow(edits.set_track(project, track, mute=True))
    feeder.join(0.5)
    rest = pull(out, 16384)  # the chunks rendered before the edit, then silence
    assert np.abs(rest[:1000]).max() > 0.4 and np.abs(rest[-4096:]).max() == 0.0
    out.stop()
    feeder.join(1.0)
    assert not feeder.is_alive()  # stopping ends the feeder too


def test_without_a_sound_card_playing_is_one_sentence() -> None:
    project, _ = sound_project()
    note = SoundOut().play(project, 0.0, 1.0)
    # on a machine with a sound card the sound plays and there is nothing to say
    assert note == "" or (note.startswith("the source sound is not played: ") and "\n" not in note)


def test_nothing_to_play_without_an_audio_track() -> None:
    assert SoundOut().play(edits.new_project(templates=False), 0.0, 1.0) == ""
