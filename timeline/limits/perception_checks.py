"""Perception findings: parts below detection, gaps too short to feel, differences below a JND."""

from __future__ import annotations

from collections import Counter
from dataclasses import replace
from itertools import combinations

import numpy as np

from timeline.limits.design import Sampled, sample, variant_project
from timeline.limits.findings import Finding, spans
from timeline.limits.frames import frames
from timeline.limits.skin import displacement_per_unit
from timeline.limits.thresholds import (
    AMPLITUDE_JND_DB,
    FORCE_JND,
    FREQUENCY_WEBER,
    TEMPORAL_RESOLUTION,
    detection_threshold,
    level_difference_db,
)
from timeline.model import Project
from timeline.plugins.device_protocol import Actuator, DeviceInfo, Hand

SILENT = 1e-9  # of the device's maximum output: below this a drive sample is silence


def below_detection(
    design: Sampled, info: DeviceInfo, actuator: Actuator | None, hand: Hand | None = None
) -> list[Finding]:
    """Whole events (drive between silences) whose every frame is below Verrillo's threshold.

    A fade that ends below the threshold is felt until it does, so only events that are never
    felt are findings. On a knob the skin moves as the hand's grip lets it (skin.py).
    """
    d = design.terms.get("d")
    if d is None or design.axis != "time":
        return []
    fr = frames(d, design.rate, design.start)
    per_unit = displacement_per_unit(info, actuator, fr.frequency, hand)
    if per_unit is None:
        return []
    moved = fr.peak * per_unit  # peak skin displacement
    needed = detection_threshold(fr.frequency)
    out = []
    for a, b in spans(fr.rms > SILENT * info.max_output):
        if (moved[a : b + 1] >= needed[a : b + 1]).any():
            continue
        worst = a + int(np.argmax(moved[a : b + 1] / needed[a : b + 1]))
        start, stop = fr.span(a, b)
        short = 20.0 * np.log10(needed[worst] / max(moved[worst], 1e-300))
        out.append(
            Finding(
                "below-detection", "perception",
                f"this part moves the skin less than a hand can detect at {fr.frequency[worst]:.0f}"
                " Hz (Verrillo's threshold)", start, stop, "time", float(moved[worst] * 1e6),
                float(needed[worst] * 1e6), "um", f"raise it by at least {short:.1f} dB or move "
                "it towards 250 Hz, where the hand is most sensitive", "d",
            )
        )  # fmt: skip
    return out


def short_gaps(design: Sampled, info: DeviceInfo) -> list[Finding]:
    """Silences between two drive events shorter than touch's temporal resolution."""
    d = design.terms.get("d")
    if d is None or design.axis != "time":
        return []
    silent = np.abs(d) <= SILENT * info.max_output
    out = []
    for a, b in spans(silent):
        length = (b + 1 - a) / design.rate
        if a == 0 or b == d.size - 1 or b - a < 1 or length >= TEMPORAL_RESOLUTION:
            continue
        out.append(
            Finding(
                "gap-too-short", "perception",
                "a silence this short is not felt: the events either side feel like one",
                design.position(a), design.position(b + 1), "time", length * 1e3,
                TEMPORAL_RESOLUTION * 1e3, "ms",
                f"lengthen the gap to at least {TEMPORAL_RESOLUTION * 1e3:.0f} ms or join the "
                "events", "d",
            )
        )  # fmt: skip
    return out


def _relative(a: np.ndarray, b: np.ndarray) -> float:
    """Largest |a - b| relative to the larger magnitude, over samples where either is not 0."""
    scale = np.maximum(np.abs(a), np.abs(b))
    used = scale > 0
    return float((np.abs(a - b)[used] / scale[used]).max()) if used.any() else 0.0


def difference(one: Sampled, two: Sampled, info: DeviceInfo) -> dict[str, float] | None:
    """How two designs differ, per measure, or None when their rhythm or layers differ.

    Measures: drive level (dB, per frame) and frequency (relative), and the relative difference
    of each of k, b, m sample by sample.
    """
    if set(one.terms) != set(two.terms):
        return None
    n = min(one.length, two.length)
    if max(one.length, two.length) - n > one.rate * TEMPORAL_RESOLUTION:
        return None  # lengths differ by more than touch resolves
    out: dict[str, float] = {}
    for term in one.terms:
        a, b = one.terms[term][:n], two.terms[term][:n]
        if term != "d":
            out[term] = _relative(a, b)
            continue
        fa, fb = frames(a, one.rate), frames(b, two.rate)
        quiet = SILENT * info.max_output
        on_a, on_b = fa.rms > quiet, fb.rms > quiet
        if (on_a != on_b).any():
            return None  # one is on where the other is silent: a rhythm difference
        levels = [
            level_difference_db(x, y) for x, y in zip(fa.rms[on_a], fb.rms[on_a], strict=True)
        ]
        out["amplitude"] = max(levels, default=0.0)
        both = on_a & (fa.frequency > 0) & (fb.frequency > 0)
        rel = (
            np.abs(fa.frequency - fb.frequency)[both] / np.minimum(fa.frequency, fb.frequency)[both]
        )
        out["frequency"] = float(rel.max()) if rel.size else 0.0
    return out


JND = {"amplitude": AMPLITUDE_JND_DB, "frequency": FREQUENCY_WEBER, "k": FORCE_JND,
       "b": FORCE_JND, "m": FORCE_JND}  # fmt: skip
UNITS = {"amplitude": "dB", "frequency": "(relative)", "k": "(relative)", "b": "(relative)",
         "m": "(relative)"}  # fmt: skip


def _sub_jnd(name: str, diff: dict[str, float], start: float, stop: float, axis: str) -> Finding:
    """A finding for two designs whose every difference is below its JND."""
    worst = max(diff, key=lambda key: diff[key] / JND[key])
    parts = ", ".join(f"{key} {diff[key]:.3g} {UNITS[key]}" for key in diff)
    return Finding(
        "sub-jnd", "perception", f"{name} differ by less than a JND ({parts})", start, stop, axis,
        diff[worst], JND[worst], UNITS[worst],
        f"make the {worst} difference at least {JND[worst]:.3g} {UNITS[worst]} or drop one",
        worst,
    )  # fmt: skip


def sub_jnd_variants(
    project: Project, info: DeviceInfo, rate: float, quality: str
) -> list[Finding]:
    """Saved variants that a hand cannot tell apart (every difference below its JND)."""
    designs = {v.name: sample(variant_project(project, v.name), rate, quality)
               for v in project.variants}  # fmt: skip
    out = []
    for a, b in combinations(designs, 2):
        diff = difference(designs[a], designs[b], info)
        if diff is not None and all(diff[k] < JND[k] for k in diff):
            one = designs[a]
            stop = one.position(one.length)
            out.append(_sub_jnd(f"variants {a!r} and {b!r}", diff, one.start, stop, one.axis))
    return out


def sub_jnd_clips(project: Project, info: DeviceInfo, rate: float, quality: str) -> list[Finding]:
    """Steps between consecutive clips of one kind and length that are smaller than a JND.

    Clips of each kind are taken in timeline order; a clip and the next one of the same length
    that differ, but by less than a JND in every measure, are a step the hand cannot feel (an
    intended crescendo or contrast that is not there). Runs of such steps make one finding.
    Identical clips are a deliberate repeat and are left alone. Each clip is rendered once, on
    its own, so the check grows with the number of clips, not with its square; a clip alone of
    its kind has no step and is not rendered.
    """
    kinds = Counter(track.kind for track in project.tracks for _ in track.clips)
    by_kind: dict[str, list[tuple[float, str, Sampled]]] = {}
    for track in project.tracks:
        lone = replace(track, mute=False, solo=False)
        for clip in track.clips if kinds[track.kind] > 1 else ():
            alone = replace(project, tracks=(replace(lone, clips=(replace(clip, start=0.0),)),))
            design = sample(alone, rate, quality)
            if design.length:
                by_kind.setdefault(track.kind, []).append((clip.start, clip.id, design))
    out = []
    for clips in by_kind.values():
        clips.sort(key=lambda c: (c[0], c[1]))
        run: list[tuple[str, str, dict[str, float]]] = []
        for (_, ia, a), (_, ib, b) in zip(clips, clips[1:], strict=False):
            diff = None
            same = abs(a.length - b.length) <= 1 and set(a.terms) == set(b.terms)
            if same and not all(np.array_equal(a.terms[t], b.terms[t]) for t in a.terms):
                diff = difference(a, b, info)
            if diff is not None and all(diff[k] < JND[k] for k in diff):
                run.append((ia, ib, diff))
                continue
            out += _step_finding(project, run)
            run = []
        out += _step_finding(project, run)
    return out


def _step_finding(project: Project, run: list[tuple[str, str, dict[str, float]]]) -> list[Finding]:
    """One finding for a run of sub-JND steps between consecutive clips."""
    if not run:
        return []
    first, last = run[0][0], run[-1][1]
    worst = max(run, key=lambda step: max(step[2][k] / JND[k] for k in step[2]))[2]
    start = project.find_clip(first)[1].start
    stop = project.find_clip(last)[1].end
    name = f"clips {first} and {last}" if len(run) == 1 else (
        f"{len(run) + 1} clips from {first} to {last}, each and the next,"
    )  # fmt: skip
    return [_sub_jnd(name, worst, start, stop, project.axis)]
