"""One mixer, many threads, and failures half way: every render equals a fresh one bit for bit.

The editor renders from several threads (findings overlay, sound feeder, export jobs, playback)
through the one shared mixer; a render can also stop half way (MemoryError, overflow). The
reference each time is a render by a new Mixer, alone, of the same project and range.
"""

from __future__ import annotations

import sys
import threading
from collections.abc import Iterator

import numpy as np
import pytest

from timeline import Mixer, edits
from timeline.bench.scenes import LargeSpec, large_project
from timeline.model import Project
from timeline.tiles import GeneratorTile

SECONDS = 8.0
THREADS = 4
ROUNDS = 40


def versions() -> list[Project]:
    """A project and two edits of it (a moved clip, a new gain), rendered in turn."""
    project = large_project(LargeSpec(tracks=6, clips=120, seconds=SECONDS, shapes=12), seed=5)
    track = next(t for t in project.tracks if t.clips)
    first, second = track.clips[0], track.clips[-1]
    moved = edits.move_clip(project, first.id, first.start + 0.25)
    louder = edits.set_clip_gain(moved, second.id, 1.7)
    return [project, moved, louder]


def fresh(project: Project) -> dict[str, np.ndarray]:
    return Mixer().render(project, 0.0, SECONDS)


def same(got: dict[str, np.ndarray], want: dict[str, np.ndarray]) -> bool:
    return got.keys() == want.keys() and all(np.array_equal(got[k], want[k]) for k in want)


@pytest.fixture
def short_switches() -> Iterator[None]:
    """Switch threads every 10 us, so renders interleave inside their sums."""
    before = sys.getswitchinterval()
    sys.setswitchinterval(1e-5)
    yield
    sys.setswitchinterval(before)


@pytest.mark.usefixtures("short_switches")
def test_four_threads_rendering_one_project_get_the_single_thread_results() -> None:
    projects = versions()
    want = [fresh(p) for p in projects]
    assert not same(want[0], want[1]) and not same(want[1], want[2])
    mixer = Mixer()
    start = threading.Barrier(THREADS)
    wrong: list[tuple[int, int]] = []
    errors: list[BaseException] = []

    def work(index: int) -> None:
        start.wait()
        for step in range(ROUNDS):
            which = (index + step) % len(projects)
            try:
                layers = mixer.render(projects[which], 0.0, SECONDS)
            except Exception as exc:  # collected: an error is a failure like a wrong number
                errors.append(exc)
                continue
            if not same(layers, want[which]):
                wrong.append((index, step))
            del layers  # hold no result, so the mixer may update its buffers in place

    threads = [threading.Thread(target=work, args=(i,)) for i in range(THREADS)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert errors == []
    assert wrong == []
    assert mixer.stats.clip_hits > 0  # the cache was shared and reused, not bypassed


def fail_once(monkeypatch: pytest.MonkeyPatch, call: int) -> list[int]:
    """Make the `call`-th generator tile render raise MemoryError; returns the call counter."""
    calls = [0]
    real = GeneratorTile.render

    def render(self: GeneratorTile, *args: object) -> np.ndarray:
        calls[0] += 1
        if calls[0] == call:
            raise MemoryError("injected")
        return real(self, *args)

    monkeypatch.setattr(GeneratorTile, "render", render)
    return calls


@pytest.mark.parametrize("call", [1, 3, 5])  # a render of the project evaluates 5 generators
def test_a_render_that_fails_half_way_leaves_the_next_render_equal_to_a_fresh_one(
    monkeypatch: pytest.MonkeyPatch, call: int
) -> None:
    projects = versions()
    want = [fresh(p) for p in projects]
    mixer = Mixer()
    calls = fail_once(monkeypatch, call)
    with pytest.raises(MemoryError):
        mixer.render(projects[1], 0.0, SECONDS)
    assert calls[0] == call
    for which in (1, 0, 2, 1):
        assert same(mixer.render(projects[which], 0.0, SECONDS), want[which]), which


def test_an_edit_whose_render_fails_leaves_the_cached_window_correct(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    projects = versions()
    mixer = Mixer()
    mixer.render(projects[0], 0.0, SECONDS)
    track = next(t for t in projects[0].tracks if t.clips)
    clip = track.clips[len(track.clips) // 2]
    edited, new_tile = edits.add_tile(
        projects[0], GeneratorTile("sine", 0.5, (("frequency", 77.0),))
    )
    edited, _ = edits.add_clip(edited, track.id, new_tile, clip.start + 0.01)
    fail_once(monkeypatch, 1)  # the one new shape: the window's parts are placed, its sum fails
    with pytest.raises(MemoryError):
        mixer.render(edited, 0.0, SECONDS)
    assert same(mixer.render(edited, 0.0, SECONDS), fresh(edited))
    assert same(mixer.render(projects[0], 0.0, SECONDS), fresh(projects[0]))
