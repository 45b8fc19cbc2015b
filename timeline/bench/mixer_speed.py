"""Mixer throughput against one memory pass, and re-render time after a 1 s clip edit.

The physical limit of mixing is touching every clip sample once: the baseline adds preallocated
arrays of the output's size into an output array until as many samples were added as the
project's clips cover. A full render (fresh mixer: every clip shape evaluated, every block summed)
is reported as a ratio to that pass; a re-render after editing one ~1 s clip as a ratio to the
full render. Both are the best of several runs measured in this process.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from timeline import edits
from timeline.bench.report import Table, best_time, figure, save
from timeline.bench.scenes import FULL, QUICK, LargeSpec, clip_samples, large_project
from timeline.model import Project
from timeline.rendering.mixer import Mixer
from timeline.signal.resample import forget_resampled

NAME = "mixer"
SUMMARY = "mixer throughput vs one memory pass; re-render after a 1 s clip edit"
TARGET_FULL = 3.0  # full render within 3x of the memory pass at `normal`
TARGET_EDIT = 0.01  # a 1 s clip edit re-renders in under 1 % of the full render


def memory_pass(total: int, n: int, repeat: int) -> float:
    """Seconds to add `total` samples into a preallocated output of n samples (best of repeat)."""
    out, src = np.zeros(n), np.ones(n)
    whole, rest = divmod(total, n)

    def run() -> None:
        for _ in range(whole):
            np.add(out, src, out=out)
        np.add(out[:rest], src[:rest], out=out[:rest])

    return best_time(run, repeat)


def fresh_render(project: Project, stop: float, quality: str = "normal") -> None:
    """A full render from scratch: a new mixer, and recordings resampled again (as in a new
    process; timeline.signal.resample keeps a recording's resampling for its next clips)."""
    forget_resampled()
    Mixer().render(project, 0.0, stop, quality=quality)


def one_second_clip(project: Project) -> tuple[str, float]:
    """The id and start of the clip whose length is closest to 1 s."""
    clip = min((c for t in project.tracks for c in t.clips), key=lambda c: abs(c.duration - 1.0))
    return clip.id, clip.start


def edit_times(project: Project, stop: float, quality: str, repeat: int) -> dict[str, float]:
    """Best re-render time after a gain edit and after a 0.1 s move of one ~1 s clip."""
    clip_id, start = one_second_clip(project)
    mixer = Mixer()
    mixer.render(project, 0.0, stop, quality=quality)
    times = {}
    for edit in ("gain", "move"):
        best = np.inf
        for i in range(repeat):
            if edit == "gain":
                edited = edits.set_clip_gain(project, clip_id, 0.5 + 0.1 * i)
            else:
                edited = edits.move_clip(project, clip_id, start + 0.1 * (i + 1))
            best = min(
                best, best_time(lambda p=edited: mixer.render(p, 0.0, stop, quality=quality), 1)
            )
        times[edit] = best
    return times


def measure(spec: LargeSpec, qualities: tuple[str, ...], repeat: int) -> list[dict]:
    """One row per quality: memory pass, full render and edit re-render times."""
    project = large_project(spec)
    stop = spec.seconds
    Mixer().render(project, 0.0, stop)  # imports and first-touch memory, not timed
    total = clip_samples(project, project.rate)
    n = int(round(stop * project.rate))
    rows = []
    for quality in qualities:
        base = memory_pass(total, n, repeat)
        full = best_time(lambda q=quality: fresh_render(project, stop, q), repeat)
        edit = edit_times(project, stop, quality, repeat)
        rows.append(dict(quality=quality, clips=sum(len(t.clips) for t in project.tracks),
                         total=total, n=n, base=base, full=full, **edit))  # fmt: skip
    return rows


def run(quick: bool, out: Path) -> list[Table]:
    spec = QUICK if quick else FULL
    repeat = 2 if quick else 3
    shared = measure(spec, ("draft", "normal", "exact"), repeat)
    # every clip its own shape, starts off the sample grid (as dragged without snapping)
    size = LargeSpec(QUICK.tracks, QUICK.clips // 2, QUICK.seconds / 2, 0, off_grid=True)
    distinct = measure(size if quick else LargeSpec(FULL.tracks, 16_000, FULL.seconds, 0, True),
                       ("normal",), 1 if quick else 2)  # fmt: skip
    table = Table(
        f"Mixer: {spec.tracks} tracks, {spec.seconds:g} s at 10 kHz (best of {repeat})",
        ["project", "quality", "clips", "clip samples", "memory pass s", "full render s",
         "full / pass", "gain edit s", "move edit s", "edit / full"],
    )  # fmt: skip
    for label, rows in (("shared shapes", shared), ("every clip distinct, off-grid", distinct)):
        for r in rows:
            edit = max(r["gain"], r["move"]) / r["full"]
            ratio = r["full"] / r["base"]
            table.rows.append([label, r["quality"], r["clips"], r["total"], r["base"], r["full"],
                               ratio, r["gain"], r["move"], edit])  # fmt: skip
    normal = next(r for r in shared if r["quality"] == "normal")
    full_ratio = normal["full"] / normal["base"]
    edit_ratio = max(normal["gain"], normal["move"]) / normal["full"]
    table.notes += [
        f"target: full render at normal within {TARGET_FULL:g}x of the memory pass: "
        f"{full_ratio:.2f}x ({'met' if full_ratio <= TARGET_FULL else 'NOT met'})",
        f"target: a 1 s clip edit re-renders in under {TARGET_EDIT:.0%} of the full render: "
        f"{edit_ratio:.2%} ({'met' if edit_ratio < TARGET_EDIT else 'NOT met'})",
        f"shared shapes: {spec.clips} clips place {spec.shapes} distinct clip shapes (a design "
        "built by duplicating and pasting); 'every clip distinct' evaluates a shape per clip",
        "memory pass: numpy adds preallocated arrays of the output's size once per clip sample",
    ]
    if quick:
        table.notes.append(
            "quick mode: the project is 10x shorter, so one edit is a larger share of it; the "
            "edit target applies to the full-size project"
        )
    plot(shared + distinct, out)
    return [table]


def plot(rows: list[dict], out: Path) -> None:
    fig, ax = figure(7.5, 4.0)
    labels, values, colors = [], [], []
    for i, r in enumerate(rows):
        tag = r["quality"] + (" (distinct)" if i >= 3 else "")
        edit = max(r["gain"], r["move"])
        bars = (("memory pass", r["base"], "0.6"), ("full render", r["full"], "C0"),
                ("1 s clip edit", edit, "C1"))  # fmt: skip
        for what, value, color in bars:
            labels.append(f"{tag}: {what}")
            values.append(value)
            colors.append(color)
    y = np.arange(len(values))[::-1]
    ax.barh(y, values, color=colors)
    ax.set_yticks(y, labels, fontsize=8)
    ax.set_xscale("log")
    ax.set_xlabel("seconds (log scale)")
    ax.set_title("Mixer: full render and edit re-render against one memory pass", fontsize=10)
    save(fig, out, "mixer_speed")
