"""`check --plot`: rendered against designed, with the findings shaded (matplotlib, no Qt)."""

from __future__ import annotations

import numpy as np

from timeline.files.atomic import write_atomically
from timeline.limits.check import Report
from timeline.limits.design import sample
from timeline.limits.rendered import Trace, knob, vibration
from timeline.model import Project
from timeline.plugins.device_protocol import Actuator, DeviceInfo, Hand

COLOURS = {"device": "#e67e22", "perception": "#8e44ad"}


def traces(
    project: Project, info: DeviceInfo, actuator: Actuator | None, hand: Hand, quality: str
) -> list[Trace]:
    """What to draw: the vibration's rendering and, on a knob, the torque it applies."""
    out = []
    shaken = vibration(sample(project, info.rate, quality), info, actuator)
    if shaken is not None:
        out.append(shaken)
    if info.kind == "kinesthetic":
        out.append(knob(project, info, hand, quality))
    return out


def plot_rendered(
    project: Project,
    info: DeviceInfo,
    actuator: Actuator | None,
    report: Report,
    path: str,
    hand: Hand,
    quality: str = "normal",
) -> None:
    """Write a PNG: each trace designed (grey) against rendered, findings shaded by area; over
    time, or over the knob's angle on a position project."""
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib import pyplot as plt

    rows = traces(project, info, actuator, hand, quality)
    fig, axes = plt.subplots(len(rows), 1, figsize=(10, 2.6 * len(rows) + 0.8), squeeze=False)
    for ax, trace in zip(axes[:, 0], rows, strict=True):
        along = trace.time if trace.angle is None else np.degrees(trace.angle)
        ax.plot(along, trace.designed * trace.scale, color="#95a5a6", lw=1.6,
                label="designed")  # fmt: skip
        ax.plot(along, trace.rendered * trace.scale, color="#c0392b", lw=0.8,
                label="rendered")  # fmt: skip
        scale = 1.0 if trace.axis == "time" else 180.0 / np.pi  # findings: s, or rad to deg
        for n, f in enumerate(f for f in report.findings if f.axis == trace.axis):
            ax.axvspan(f.start * scale, f.stop * scale, color=COLOURS[f.area], alpha=0.15,
                       lw=0, label=None if n else "findings")  # fmt: skip
        ax.set_ylabel(f"{trace.label}\n[{trace.unit}]", fontsize=8)
        ax.set_title(f"largest gap {trace.worst_gap() * trace.scale:.3g} {trace.unit}",
                     fontsize=8, loc="right")  # fmt: skip
        ax.grid(True, alpha=0.3)
        ax.legend(loc="upper right", fontsize=8)
    axes[-1, 0].set_xlabel("time [s]" if rows[-1].axis == "time" else "knob angle [deg]")
    kinds = sorted(report.kinds())
    fig.suptitle(
        f"rendered against designed on {info.name}: "
        + (f"{len(report.findings)} findings ({', '.join(kinds)})" if kinds else "no findings"),
        fontsize=9,
    )
    fig.tight_layout()
    write_atomically(path, lambda tmp: fig.savefig(tmp, dpi=110, format="png"))
    plt.close(fig)
