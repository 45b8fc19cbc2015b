"""`haptic-timeline play PROJECT`: feel a project on a device, with a summary, CSV and plot."""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path
from typing import TYPE_CHECKING

from timeline.cli.device_options import device_options
from timeline.cli.units import Typed, amount, axis_value, on_axis
from timeline.errors import HapticTimelineError
from timeline.files.atomic import check_target
from timeline.signal.render_presets import DEFAULT_QUALITY, PRESETS

if TYPE_CHECKING:  # numpy, the devices and the mixer load when a project is played, not for --help
    import numpy as np

    from timeline.model import Project
    from timeline.plugins.device_protocol import DeviceInfo, PositionProgram, Telemetry
    from timeline.rendering.playback import Playback


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("play", help="play a project on a device (the simulated knob by default)")
    p.add_argument("project", help="a .htl project file")
    p.add_argument("--device", default="sim", help="device plugin: sim (default), usb, audio")
    p.add_argument(
        "--device-option",
        action="append",
        default=[],
        metavar="KEY=VALUE",
        help="an option for the device plugin, e.g. emulate=true or vid=0x1209 (repeatable)",
    )
    p.add_argument(
        "--hand",
        default="hold",
        help=(
            "hold (default), free, turn:DEG_PER_S or push:MNM; a measured hand by name (pinch,"
            " grasp) or before a mode with a dash (pinch-turn:90); see docs/devices.md"
        ),
    )
    p.add_argument("--duration", type=axis_value,
                   help="seconds to play, 2 or 2s (default: the project's)")  # fmt: skip
    p.add_argument("--origin", type=axis_value, help="position projects: the table angle where "
                   "the knob starts, in degrees (90, 90deg or 1.57rad)")  # fmt: skip
    p.add_argument("-o", "--output", help="write telemetry to this .csv")
    p.add_argument("--plot", help="write a plot of layers, angle and torque to this .png")
    p.add_argument("--quality", default=DEFAULT_QUALITY, choices=list(PRESETS))
    p.set_defaults(func=run)


class _Progress:
    """Progress on stderr: a rewritten line on a terminal, a few lines otherwise."""

    def __init__(self) -> None:
        self.tty = sys.stderr.isatty()
        self.next_report = 0.0

    def __call__(self, played: float, total: float | None) -> None:
        fraction = played / total if total else None
        if self.tty:
            text = f"{played:7.2f} s" + (f" / {total:.2f} s" if total else "")
            print(f"\rplaying {text}", end="", file=sys.stderr, flush=True)
        elif fraction is not None and fraction >= self.next_report:
            print(f"playing {100 * min(fraction, 1.0):3.0f}%", file=sys.stderr, flush=True)
            self.next_report = math.floor(fraction * 4 + 1) / 4

    def done(self) -> None:
        if self.tty:
            print(file=sys.stderr)


def run(args: argparse.Namespace) -> int:
    from timeline.files.projectfile import load
    from timeline.plugins.device_protocol import Hand, open_device
    from timeline.rendering.aliasing import aliasing_notes
    from timeline.rendering.playback import prepare

    project = load(args.project)
    hand = Hand.parse(args.hand)
    duration = None
    if args.duration is not None:
        duration = on_axis(args.duration, "time", "--duration", owner="--duration")
        if duration <= 0:
            raise HapticTimelineError(
                f"--duration must be a positive number of seconds, not {args.duration.text}"
            )
    origin = _origin(project, args.origin, Path(args.project).name)
    _check_outputs(args)
    progress = _Progress()
    with open_device(args.device, **device_options(args.device_option)) as device:
        _check_duration(duration, device.info)
        playback = prepare(project, device.info, duration, hand, args.quality, origin)
        rate = device.info.rate if project.axis == "time" else project.rate
        for note in aliasing_notes(project, rate):
            print(f"haptic-timeline: warning: {note}", file=sys.stderr)
        device.warm_up()  # compiled code loads now, not while a real-time device waits
        telemetry = device.play(playback.program, hand, progress)
    progress.done()
    print(f"{Path(args.project).name} on {device.info.name} with hand {hand}")
    for line in telemetry.summary(device.info.kind):
        print(f"  {line}")
    if args.output:
        telemetry.write_csv(args.output, playback.layer_names)
        print(f"telemetry -> {args.output}", file=sys.stderr)
    if args.plot:
        title = f"{Path(args.project).stem} on {device.info.name}, hand {hand}"
        plot_telemetry(telemetry, playback, args.plot, title, device.info.max_output)
        print(f"plot -> {args.plot}", file=sys.stderr)
    return 0


def _origin(project: Project, typed: Typed | None, name: str) -> float | None:
    """--origin in radians: only on a position project, and on its table (one sentence if not)."""
    if typed is None:
        return None
    if project.axis != "position":
        raise HapticTimelineError(
            f"--origin is where the knob starts on a position project's table; {name} is on "
            "the time axis"
        )
    origin = on_axis(typed, "position", "--origin")
    starts = [c.start for t in project.tracks for c in t.clips]
    low, high = min([0.0, *starts]), project.duration
    if not low <= origin <= high:
        raise HapticTimelineError(
            f"--origin {amount(origin, 'position')} is outside {name}'s table "
            f"({amount(low, 'position')} to {amount(high, 'position')})"
        )
    return origin


def _check_duration(duration: float | None, info: DeviceInfo) -> None:
    """Refuse a --duration longer than one play can hold, in seconds and hours."""
    from timeline.rendering.mixer import MAX_SAMPLES

    longest = MAX_SAMPLES / info.rate
    if duration is not None and duration > longest:
        raise HapticTimelineError(
            f"--duration {duration:g} s is longer than {info.name} can play in one go "
            f"({longest:.0f} s, {longest / 3600:.1f} hours, at {info.rate:g} Hz)"
        )


def _check_outputs(args: argparse.Namespace) -> None:
    """Refuse an unwritable -o or --plot before playing, not after."""
    if args.output:
        suffix = Path(args.output).suffix.lower()
        if suffix != ".csv":
            raise HapticTimelineError(
                f"-o writes the telemetry as CSV: give a file ending in .csv, not "
                f"{suffix or 'one without an extension'}"
            )
        check_target(args.output)
    if args.plot:
        check_target(args.plot)
        from matplotlib.figure import Figure

        kinds = Figure().canvas.get_supported_filetypes()
        suffix = Path(args.plot).suffix.lower().lstrip(".")
        if suffix not in kinds:
            raise HapticTimelineError(
                f"--plot cannot write .{suffix or '(no extension)'} files "
                f"(choose from {', '.join(sorted(kinds))})"
            )


def _layer_axis(ax, t: np.ndarray, values: np.ndarray, kind_id: str) -> None:
    from timeline.plugins.track_kinds import track_kind

    try:
        kind = track_kind(kind_id.split("+")[0])
        scale, unit, colour, label = kind.display_scale, kind.display_unit, kind.colour, kind.label
    except HapticTimelineError:
        scale, unit, colour, label = 1.0, "", "grey", kind_id
    ax.plot(t, values * scale, color=colour, lw=1.0)
    ax.set_ylabel(f"{label}\n[{unit}]")


def plot_telemetry(
    telemetry: Telemetry, playback: Playback, path: str, title: str, max_torque: float
) -> None:
    """Write a PNG: each layer, the angle and the torque over time (position mode: and vs angle)."""
    import matplotlib
    import numpy as np

    matplotlib.use("Agg")
    from matplotlib import pyplot as plt

    from timeline.plugins.device_protocol import PositionProgram

    t = telemetry.time
    layers = [(k, v) for k, v in playback.layer_names.items() if k in telemetry.layers]
    program = playback.program
    position = program if isinstance(program, PositionProgram) else None
    origin = None if position is None else position.origin
    rows = len(layers) + 3 + (origin is not None)
    heights = [1.0] * (len(layers) + 3) + ([2.2] if origin is not None else [])
    fig, axes = plt.subplots(
        rows, 1, figsize=(10, 1.7 * sum(heights) + 0.8), height_ratios=heights, squeeze=False
    )
    axes = axes[:, 0]
    for ax, (key, kind_id) in zip(axes, layers, strict=False):
        _layer_axis(ax, t, telemetry.layers[key], kind_id)
    ax_theta, ax_tau, ax_energy = axes[len(layers) : len(layers) + 3]
    shown = np.degrees(telemetry.angle + (origin or 0.0))
    ax_theta.plot(t, shown, color="black", lw=1.0)
    ax_theta.set_ylabel("angle\n[deg]" + ("" if origin is None else " (table)"))
    ax_tau.plot(t, telemetry.torque * 1e3, color="#c0392b", lw=1.0)
    for level in (max_torque, -max_torque):
        ax_tau.axhline(level * 1e3, color="grey", ls="--", lw=0.8)
    ax_tau.set_ylabel("applied\ntorque [mNm]")
    _shade(ax_tau, t, telemetry.saturated, "orange", "saturated")
    for flag in telemetry.flags:
        mask = np.isin(t, flag.times)
        _shade(ax_tau, t, mask, "red", f"flag: {flag.kind}")
    if ax_tau.get_legend_handles_labels()[0]:
        ax_tau.legend(loc="upper right", fontsize=8)
    from timeline.plugins.device_protocol.telemetry import ENERGY_TOLERANCE

    energy = np.where(np.abs(telemetry.energy) <= ENERGY_TOLERANCE, 0.0, telemetry.energy)
    ax_energy.plot(t, energy * 1e3, color="#34495e", lw=1.0)  # round-off drawn as 0: no 1e-62 axis
    for ax in axes[: len(layers) + 3]:
        ax.ticklabel_format(axis="y", useOffset=False)
    ax_energy.axhline(0.0, color="grey", lw=0.5)
    ax_energy.set_ylabel("energy by\ndevice [mJ]")
    time_axes = axes[: len(layers) + 3]
    for ax in time_axes:
        ax.grid(True, alpha=0.3)
        ax.sharex(time_axes[0])
    for ax in time_axes[:-1]:
        ax.tick_params(labelbottom=False)
    time_axes[-1].set_xlabel("time [s]")
    if position is not None:
        _feel_map(axes[-1], telemetry, position)
    fig.suptitle(title + "\n" + "; ".join(telemetry.summary()[1:4]), fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def _shade(ax, t: np.ndarray, mask: np.ndarray, colour: str, label: str) -> None:
    """Shade the time spans where mask is True."""
    import numpy as np

    if not mask.any():
        return
    edges = np.diff(np.concatenate([[0], mask.astype(np.int8), [0]]))
    starts, stops = np.flatnonzero(edges == 1), np.flatnonzero(edges == -1) - 1
    dt = 1.0 / (len(t) / (t[-1] - t[0])) if len(t) > 1 else 0.0
    for n, (a, b) in enumerate(zip(starts, stops, strict=True)):
        ax.axvspan(t[a], t[b] + dt, color=colour, alpha=0.25, label=None if n else label, lw=0)


def _feel_map(ax, telemetry: Telemetry, program: PositionProgram) -> None:
    """Position mode: the torque table over angle, with the torque felt along the knob's path."""
    import numpy as np

    table = program.table
    ax.plot(np.degrees(table.angles()), table.torque * 1e3, color="#f18f01", lw=1.2,
            label="torque table T(angle)")  # fmt: skip
    ax.plot(np.degrees(program.origin + telemetry.angle), telemetry.torque * 1e3, color="#c0392b",
            lw=0.8, alpha=0.8, label="torque applied along the path")  # fmt: skip
    ax.axhline(0.0, color="grey", lw=0.5)
    ax.axvline(np.degrees(program.origin), color="black", ls=":", lw=0.8, label="start")
    ax.set_xlabel("angle [deg]")
    ax.set_ylabel("torque\n[mNm]")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="upper right", fontsize=8)
