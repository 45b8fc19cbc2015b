"""Quality presets: time per rendered second against error on fixed scenes.

Each preset (and candidate presets that differ in one parameter) renders each scene with a fresh
mixer; the error is against the scene's float64 reference (exact generator, spline and fade
formulas; for recordings the in-band tones they were made of), relative to full scale. Errors in
the first and last 10 ms of a recording are excluded (a band-limited resampler rings at a cut).
Stop-band rejection: a 48 kHz recording of a 7.3 kHz tone, above the 5 kHz Nyquist, rendered at
10 kHz; the level of its alias at 2.7 kHz in dB re the tone (more negative is better).
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np

from timeline.bench.report import Table, best_cpu_time, figure, save
from timeline.bench.scenes import RECORDING_RATE, SCENE_RATE, Scene, quality_scenes
from timeline.model import Project
from timeline.plugins.track_kinds import track_kind
from timeline.rendering.mixer import Mixer
from timeline.signal.render_presets import PRESETS, QualityPreset
from timeline.signal.resample import forget_resampled
from timeline.tiles import SampledTile

NAME = "quality"
SUMMARY = "quality presets: time per rendered second against error, Pareto plot"
EDGE = 0.01  # s excluded at a recording's ends
ALIAS_TONE = 7_300.0  # Hz, aliases to 10 kHz - 7.3 kHz = 2.7 kHz


def candidates() -> dict[str, QualityPreset]:
    """The presets, and variants of draft that differ in one parameter."""
    found = dict(PRESETS)
    draft = PRESETS["draft"]
    for d in (1, 2, 4, 8):
        if d != draft.control_decimation:
            found[f"draft, decimation {d}"] = replace(
                draft, name=f"draft-d{d}", control_decimation=d
            )
    other = np.float64 if draft.numpy_dtype == np.float32 else np.float32
    found[f"draft, {np.dtype(other).name}"] = replace(draft, name="draft-dtype", dtype=other)
    found["draft, cubic interpolation"] = replace(draft, name="draft-cubic", interpolation="cubic")
    return found


def errors(scene: Scene, q: QualityPreset) -> tuple[float, float, np.ndarray]:
    """Max abs and RMS error (full-scale units) and the rendered shape."""
    full = track_kind("drive").full_scale
    seconds = len(scene.reference) / SCENE_RATE
    out = Mixer().render(scene.project, 0.0, seconds, SCENE_RATE, q)["drive"] / full
    err = np.asarray(out, dtype=np.float64) - scene.reference
    if scene.resampled:
        edge = int(EDGE * SCENE_RATE)
        err = err[edge:-edge]
    return float(np.max(np.abs(err))), float(np.sqrt(np.mean(err**2))), out


def cold_render(project: Project, seconds: float, q: QualityPreset) -> None:
    """A render from scratch: a fresh mixer and no recording kept resampled from an earlier
    render (the resampler's cache is process-wide: without clearing it, every timing after the
    first would skip the resampling)."""
    forget_resampled()
    Mixer().render(project, 0, seconds, SCENE_RATE, q)


def rejection(q: QualityPreset, seconds: float) -> float:
    """Alias level (dB re the tone) of a 7.3 kHz tone in a 48 kHz recording rendered at 10 kHz."""
    from timeline.bench.scenes import _one_clip

    t48 = np.arange(int(seconds * RECORDING_RATE)) / RECORDING_RATE
    project = _one_clip(SampledTile(np.sin(2 * np.pi * ALIAS_TONE * t48), RECORDING_RATE), seconds)
    y = Mixer().render(project, 0.0, seconds, SCENE_RATE, q)["drive"]
    y = np.asarray(y, dtype=np.float64) / track_kind("drive").full_scale
    core = slice(len(y) // 4, 3 * len(y) // 4)
    t = np.arange(len(y))[core] / SCENE_RATE
    alias = SCENE_RATE - ALIAS_TONE
    basis = np.column_stack([np.sin(2 * np.pi * alias * t), np.cos(2 * np.pi * alias * t)])
    coef, *_ = np.linalg.lstsq(basis, y[core], rcond=None)
    return float(20 * np.log10(max(float(np.hypot(*coef)), 1e-12)))


def run(quick: bool, out: Path) -> list[Table]:
    seconds = 1.0 if quick else 4.0
    repeat = 3 if quick else 7
    scenes = quality_scenes(seconds)
    Mixer().render(scenes[2].project, 0.0, 0.1)  # imports, not timed
    table = Table(
        f"Quality presets on fixed scenes ({seconds:g} s each at 10 kHz, best of {repeat})",
        ["preset", "scene", "ms per rendered s", "max abs error", "RMS error", "stop-band dB"],
    )
    summary = Table(
        "Quality presets overall (sum of times, worst errors over the scenes)",
        [
            "preset",
            "ms per rendered s",
            "worst max abs",
            "worst RMS shapes",
            "worst RMS recordings",
            "stop-band dB",
        ],
    )
    points: dict[str, tuple[Point, Point]] = {}  # (shapes, recordings) per preset
    for label, q in candidates().items():
        stop = rejection(q, seconds)
        total, worst = 0.0, {True: 0.0, False: 0.0}
        times: dict[bool, list[float]] = {True: [], False: []}
        worst_max = 0.0
        for scene in scenes:
            t = best_cpu_time(lambda s=scene, q=q: cold_render(s.project, seconds, q), repeat)
            peak, rms, _ = errors(scene, q)
            per_second = 1e3 * t / seconds
            table.rows.append([label, scene.name, per_second, peak, rms,
                               stop if scene.resampled else "-"])  # fmt: skip
            total += per_second / len(scenes)
            times[scene.resampled].append(per_second)
            worst_max = max(worst_max, peak)
            worst[scene.resampled] = max(worst[scene.resampled], rms)
        summary.rows.append([label, total, worst_max, worst[False], worst[True], stop])
        points[label] = (
            (float(np.mean(times[False])), worst[False]),
            (float(np.mean(times[True])), worst[True]),
        )
    summary.notes += [
        "time: CPU time of this process (best of the repeats: what a render costs, whatever else "
        "the machine runs) while a fresh mixer renders the one-clip scene (shape evaluation, "
        "resampling, mixing) with the resampler's cache cleared before each timing; mean over "
        "the scenes",
        "errors: relative to full scale, against exact float64 values",
    ]
    pareto(points, out)
    return [summary, table]


Point = tuple[float, float]  # (ms per rendered second, worst RMS error)


def pareto(points: dict[str, tuple[Point, Point]], out: Path) -> None:
    """Time against error per preset: shapes on the left, recordings on the right."""
    fig, axes = figure(11.0, 4.5, ncols=2)
    floor = 1e-17
    titles = ("generators, spline, fades", "48 kHz recordings (plain and stretched)")
    for col, (ax, title) in enumerate(zip(axes, titles, strict=True)):
        front, best = [], np.inf
        for t, err in sorted(p[col] for p in points.values()):
            if err < best:
                best = err
                front.append((t, max(best, floor)))
        xs, ys = zip(*front, strict=True)
        ax.step(xs, ys, where="post", color="0.7", label="Pareto front", zorder=1)
        for i, (label, pair) in enumerate(points.items()):
            t, err = pair[col]
            ax.scatter([t], [max(err, floor)], s=45, color=f"C{i}", zorder=2, label=label)
        ax.set_yscale("log")
        ax.set_xlabel("ms per rendered second (mean over these scenes)")
        ax.set_ylabel("worst RMS error (full scale)")
        ax.set_title(title, fontsize=10)
    axes[1].legend(fontsize=7, loc="center right")
    fig.suptitle("Quality presets: time against error", fontsize=11)
    save(fig, out, "quality_pareto")
