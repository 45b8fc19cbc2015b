"""`haptic-timeline check PROJECT`: the device and perception limits a design crosses.

Exit status: 0 when nothing is found, 3 when there are findings, 1 on an error.
"""

from __future__ import annotations

import argparse
import json
import sys
from dataclasses import asdict
from pathlib import Path
from typing import TYPE_CHECKING

from timeline.cli.device_options import device_options
from timeline.limits.actuators import PROFILES
from timeline.signal.render_presets import DEFAULT_QUALITY, PRESETS

if TYPE_CHECKING:  # the limits, devices and mixer load when a design is checked, not for --help
    from timeline.limits.check import Report
    from timeline.limits.findings import Finding
    from timeline.plugins.device_protocol import DeviceInfo, Hand

FOUND = 3


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("check", help="list the device and perception limits a design crosses")
    p.add_argument("project", help="a .htl project file")
    p.add_argument("--device", default="sim", help="device plugin whose limits apply (sim)")
    p.add_argument("--device-option", action="append", default=[], metavar="KEY=VALUE",
                   help="an option for the device plugin (repeatable)")  # fmt: skip
    p.add_argument("--actuator", help=f"vibration actuator: {', '.join(PROFILES)}, lra:F0[:Q] "
                   "or voice-coil:LOW-HIGH (default: the device's own)")  # fmt: skip
    p.add_argument("--json", action="store_true", help="print the findings as JSON")
    p.add_argument("--plot", help="write rendered against designed to this .png")
    p.add_argument("--hand", default="hold",
                   help="the hand on a knob, as in play: hold (default), free, turn:DEG_PER_S, "
                   "push:MNM, pinch, grasp, or a named hand and a mode (grasp-turn:90); its grip "
                   "sets how far the drive moves the skin and what --plot renders")  # fmt: skip
    p.add_argument("--quality", default=DEFAULT_QUALITY, choices=list(PRESETS))
    p.set_defaults(func=run)


def device_limits(info: DeviceInfo) -> dict[str, float]:
    """The limits a device's declarations imply (empty when it declares no dynamics; the
    passive stiffness alone when it does not declare its estimator)."""
    from timeline.limits import servo

    dyn = info.dynamics
    if dyn is None or info.kind != "kinesthetic":
        return {}
    limits = {"passive_stiffness": float(servo.passive_stiffness(dyn.damping, 0.0, info.period,
                                                                 dyn.delay))}  # fmt: skip
    if dyn.estimator_declared:
        low, high = servo.mass_limits(dyn, info.period)
        limits.update(damping=servo.damping_limit(dyn, info.period), mass_low=low, mass_high=high)
    return limits


def finding_json(finding: Finding) -> dict[str, object]:
    """A finding as JSON, its span in the units a person reads (`span_unit`: s, or deg)."""
    from timeline.edits.naming import display_unit, displayed

    out = finding.as_dict()
    for key in ("start", "stop"):
        if isinstance(out[key], float):
            out[key] = displayed(out[key], finding.axis)  # type: ignore[arg-type]
    out["span_unit"] = display_unit(finding.axis)
    return out


def as_json(path: str, info: DeviceInfo, report: Report, hand: Hand) -> str:
    device = asdict(info)
    return json.dumps(
        {
            "project": path,
            "device": device,
            "hand": str(hand),
            "limits": device_limits(info),
            "findings": [finding_json(f) for f in report.findings],
            "notes": list(report.notes),
        },
        indent=2,
    )


def run(args: argparse.Namespace) -> int:
    from timeline.files.projectfile import load
    from timeline.limits.actuators import actuator
    from timeline.limits.check import check
    from timeline.plugins.device_protocol import Hand, open_device

    project = load(args.project)
    hand = Hand.parse(args.hand)
    chosen = actuator(args.actuator) if args.actuator else None
    options = device_options(args.device_option)
    with open_device(args.device, **options) as device:
        info = device.info
    report = check(project, info, chosen, args.quality, hand)
    if args.json:
        print(as_json(args.project, info, report, hand))
    else:
        name = Path(args.project).name
        count = len(report.findings)
        print(f"{name} on {info.name}: {count or 'no'} finding{'' if count == 1 else 's'}")
        for finding in report.findings:
            print(f"  {finding.describe()}")
        for note in report.notes:
            print(f"note: {note}", file=sys.stderr)
    if args.plot:
        from timeline.limits.plot import plot_rendered

        plot_rendered(project, info, chosen or info.actuator, report, args.plot, hand, args.quality)
        print(f"plot -> {args.plot}", file=sys.stderr)
    return FOUND if report.findings else 0
