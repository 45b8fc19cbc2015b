"""View > Show rendered by device on a long design: what it costs the GUI thread at each zoom.

A 10-minute trace at 10 kHz (6 million samples, a 5 Hz sine at full torque). The findings
worker builds its peaks once (trace_peaks.py, off the GUI thread); at each zoom the editor makes
the lane's curve item and paints one 1,500 px screen of it in the middle of the design. Both are
reported against a baseline measured in the same process: one numpy pass over the samples
(their minimum and maximum), the least any drawing that touched every sample could cost.

    QT_QPA_PLATFORM=offscreen python benchmarks/rendered_overlay.py [--minutes 10]
"""

from __future__ import annotations

import argparse
import os
import time

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

import numpy as np  # noqa: E402
from PySide6.QtCore import QRectF  # noqa: E402
from PySide6.QtGui import QImage, QPainter  # noqa: E402
from PySide6.QtWidgets import QApplication, QStyleOptionGraphicsItem  # noqa: E402

from timeline import edits  # noqa: E402
from timeline.gui.geometry import Geometry  # noqa: E402
from timeline.gui.rendered_overlay import curves, peaks_of  # noqa: E402
from timeline.limits.rendered import Trace  # noqa: E402

RATE = 10_000.0
ZOOMS = (2.5, 200.0, 20_000.0, 1e6)  # px per second: whole design on a screen ... 100 px/sample
SCREEN = 1500.0  # px


def best(fn, repeat: int = 5) -> float:  # noqa: ANN001
    """Least wall time of `repeat` calls (s)."""
    out = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        out.append(time.perf_counter() - t0)
    return min(out)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--minutes", type=float, default=10.0)
    args = parser.parse_args()
    _app = QApplication.instance() or QApplication([])
    seconds = 60.0 * args.minutes
    t = np.arange(int(seconds * RATE)) / RATE
    torque = 0.18 * np.sin(2 * np.pi * 5.0 * t)
    trace = Trace("drive", "mNm", 1e3, t, torque, torque, step=1.0 / RATE)
    project, _ = edits.add_track(edits.new_project(), "drive")
    baseline = best(lambda: (torque.min(), torque.max()))
    worker = best(lambda: peaks_of(trace), repeat=3)
    peaks = peaks_of(trace)
    trace.worst_gap()  # computed once per trace, then cached
    print(f"{t.size:,} samples; baseline (numpy min and max over them): {1e3 * baseline:.2f} ms")
    print(f"peaks, in the findings worker: {1e3 * worker:.0f} ms ({worker / baseline:.0f}x)")
    print("| px per second | make the curve [ms] | paint one screen [ms] | both / baseline |")
    print("|---|---|---|---|")
    for px in ZOOMS:
        g = Geometry(px)
        (item,) = curves(project, [trace], [peaks], g)
        image = QImage(int(SCREEN), g.lane_height, QImage.Format.Format_ARGB32)
        option = QStyleOptionGraphicsItem()
        left = min(g.x(seconds / 2), max(0.0, g.x(seconds) - SCREEN))
        option.exposedRect = QRectF(left, 0.0, SCREEN, g.lane_height)

        def paint(item=item, image=image, option=option) -> None:  # noqa: ANN001
            painter = QPainter(image)
            painter.translate(-option.exposedRect.left(), 0.0)
            item.paint(painter, option)
            painter.end()

        make = best(lambda g=g: curves(project, [trace], [peaks], g))
        draw = best(paint)
        print(f"| {px:g} | {1e3 * make:.2f} | {1e3 * draw:.2f} | {(make + draw) / baseline:.2f}x |")


if __name__ == "__main__":
    main()
