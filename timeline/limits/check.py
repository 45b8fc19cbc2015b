"""Check a project against a device's rendering limits and the hand's perception limits."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from timeline.limits import device_checks, perception_checks
from timeline.limits.design import sample
from timeline.limits.findings import Finding
from timeline.model import Project
from timeline.plugins.device_protocol import Actuator, DeviceInfo, Hand

MAX_CLIPS_COMPARED = 500  # beyond this, clip-to-clip JND steps are not checked (say so)


@dataclass(frozen=True)
class Report:
    """Every finding in timeline order, and notes on checks that could not run (and why)."""

    findings: tuple[Finding, ...]
    notes: tuple[str, ...]

    def kinds(self) -> set[str]:
        return {f.kind for f in self.findings}


def check(
    project: Project,
    info: DeviceInfo,
    actuator: Actuator | None = None,
    quality: str = "normal",
    hand: Hand | None = None,
    interrupt: Callable[[], None] = lambda: None,
) -> Report:
    """All findings for a project played on a device (and, for vibration, an actuator).

    `actuator` defaults to the one the device declares; `hand` (default `hold`) is the hand on a
    knob, whose grip sets how far its drive moves the skin. `interrupt` is called between
    steps and may raise to abandon the check (the editor stops a check an edit made stale).
    """
    actuator = actuator or info.actuator
    hand = hand or Hand("hold")
    interrupt()
    design = sample(project, info.rate, quality)
    notes = []
    if info.kind == "kinesthetic":
        if info.dynamics is None:
            notes.append(
                f"{info.name} does not declare its inertia and damping: stability not checked"
            )
        elif not info.dynamics.estimator_declared:
            notes.append(
                f"{info.name} does not declare its velocity and acceleration estimator: "
                "damping and mass limits not checked (stiffness and saturation are)"
            )
    vibration = "d" in design.terms and project.axis == "time" and info.kind == "vibrotactile"
    if vibration and actuator is None:
        notes.append("no actuator profile: band and detection not checked (use --actuator)")
    if info.slew is None:
        notes.append(f"{info.name} declares no slew limit")
    knob_drive = "d" in design.terms and info.kind == "kinesthetic" and actuator is None
    if knob_drive and project.axis == "time" and not hand.touches:
        notes.append("the hand lets go of the knob (free): detection not checked")
    if project.axis == "position":
        notes.append("position project: gaps, detection and slew depend on the turning speed "
                     "and are checked on time projects only")  # fmt: skip
    clips = sum(len(t.clips) for t in project.tracks)
    compare_clips = clips <= MAX_CLIPS_COMPARED
    if not compare_clips:
        notes.append(f"{clips} clips: steps between clips are compared up to "
                     f"{MAX_CLIPS_COMPARED} clips only")  # fmt: skip
    steps = [
        lambda: device_checks.saturation(design, info),
        lambda: device_checks.stability(design, info, interrupt),
        lambda: device_checks.slew(design, info),
        lambda: device_checks.actuator_band(design, info, actuator),
        lambda: perception_checks.below_detection(design, info, actuator, hand),
        lambda: perception_checks.short_gaps(design, info),
        lambda: (
            perception_checks.sub_jnd_clips(project, info, design.rate, quality)
            if compare_clips
            else []
        ),  # fmt: skip
        lambda: perception_checks.sub_jnd_variants(project, info, design.rate, quality),
    ]
    findings: list[Finding] = []
    for step in steps:
        interrupt()
        findings += step()
    findings.sort(key=lambda f: (f.start, f.kind))
    return Report(tuple(findings), tuple(notes))
