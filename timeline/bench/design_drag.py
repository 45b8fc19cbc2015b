"""Dragging a vibration design: what one mouse move costs when the design's emphasis clips come
along (the editor's move gesture: the pressed clip moved, the others shifted in one pass).

Against two baselines run in the same process: moving the design's clip alone, and moving each
emphasis clip in turn with move_clip (how the drag worked before edits.shift_clips).
"""

from __future__ import annotations

import time
from collections.abc import Callable
from pathlib import Path

from timeline import edits
from timeline.bench.report import Table
from timeline.edits.vibration import Emphasis, VibrationDesign, place_design, with_emphasis
from timeline.model import Project

NAME = "design-drag"
SUMMARY = "one mouse move of a design clip dragging its emphasis clips, against moving each"
LENGTH = 10.0  # s: the design; its emphasis spread evenly over it
ONE_BY_ONE_MAX = 3000  # emphasis counts above this skip the quadratic baseline


def run(quick: bool, out: Path) -> list[Table]:
    table = Table(
        "Drag a design with its emphasis: one mouse move's edit (best of repeats, in-process)",
        ["emphasis clips", "drag step ms", "one by one ms", "speed-up", "design alone ms"],
    )
    for count in (100, 1000) if quick else (100, 1000, 3000, 10_000):
        project = _design(count)
        clip = project.tracks[0].clips[0].id
        step = _best(lambda p=project, c=clip: _drag_step(p, c, 0.1))
        alone = _best(lambda p=project, c=clip: edits.move_clip(p, c, 0.1))
        if count <= ONE_BY_ONE_MAX:
            slow = _best(lambda p=project, c=clip: _one_by_one(p, c, 0.1), repeats=1)
            table.rows.append(
                [
                    count,
                    f"{1e3 * step:.2f}",
                    f"{1e3 * slow:.1f}",
                    f"{slow / step:.0f}x",
                    f"{1e3 * alone:.3f}",
                ]
            )
        else:
            table.rows.append([count, f"{1e3 * step:.2f}", "—", "—", f"{1e3 * alone:.3f}"])
    table.notes.append(
        f"a {LENGTH:g} s design, its emphasis on the Emphasis track below, shifted 0.1 s; the "
        "editor does this edit once per mouse move while dragging"
    )
    return [table]


def _design(count: int) -> Project:
    accents = tuple(Emphasis(LENGTH * k / count, 0.5, 0.5) for k in range(count))
    design = VibrationDesign(((0.0, 0.5), (LENGTH, 0.5)), ((0.0, 0.5),), accents, LENGTH)
    return place_design(edits.new_project(templates=False), design)


def _drag_step(project: Project, clip_id: str, shift: float) -> Project:
    others = with_emphasis(project, [clip_id])[1:]
    start = project.find_clip(clip_id)[1].start + shift
    return edits.shift_clips(edits.move_clip(project, clip_id, start), others, shift)


def _one_by_one(project: Project, clip_id: str, shift: float) -> Project:
    for other in with_emphasis(project, [clip_id]):
        project = edits.move_clip(project, other, project.find_clip(other)[1].start + shift)
    return project


def _best(work: Callable[[], object], repeats: int = 5) -> float:
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        work()
        times.append(time.perf_counter() - t0)
    return min(times)
