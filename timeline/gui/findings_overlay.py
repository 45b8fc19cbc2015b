"""Findings on the lanes: where the design crosses a device or perception limit, kept current.

After each edit (debounced) the project is checked in a worker thread against the player's
device (timeline.limits.check); the result shades the spans on the lanes whose layer it is
about (device limits orange, perception purple; hover for the sentence) and puts one line in
the message bar when the findings change. While View > Show rendered by device is on, the same
worker also computes what the device will output (rendered_overlay) and the lanes show it.
"""

from __future__ import annotations

from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from typing import TYPE_CHECKING

from PySide6.QtCore import QObject, QRectF, Qt, QTimer, Signal
from PySide6.QtGui import QBrush, QColor, QPainter, QPen
from PySide6.QtWidgets import QGraphicsRectItem

from timeline.errors import HapticTimelineError
from timeline.limits.check import Report, check
from timeline.model import Project
from timeline.plugins.device_protocol import DeviceInfo, Hand, open_device
from timeline.plugins.track_kinds import track_kind

from .rendered_overlay import RenderedLayer, peaks_of
from .trace_peaks import Peaks

if TYPE_CHECKING:  # scipy loads with the first rendering, not at start-up
    from timeline.limits.rendered import Trace

DELAY_MS = 250  # after the last edit
MAX_LIVE_SAMPLES = 6_000_000  # 10 minutes at 10 kHz: longer designs are checked by the CLI
COLOURS = {"device": QColor(230, 126, 34, 60), "perception": QColor(142, 68, 173, 50)}
EDGES = {"device": QColor(211, 84, 0), "perception": QColor(110, 44, 140)}
LAYER_OF = {"amplitude": "d", "frequency": "d"}  # a sub-JND measure's layer
SHADE_Z = 15  # above clips, below the playhead and cursor


@dataclass(frozen=True)
class Checked:
    """What the worker found: the report and, when asked for, the rendered traces."""

    report: Report
    traces: tuple[Trace, ...] = ()
    peaks: tuple[Peaks, ...] = ()  # each trace's, ready to draw at any zoom
    unrendered: str = ""  # why the traces could not be computed, when they were asked for


class FindingShade(QGraphicsRectItem):
    """One finding's span on one lane: hatched, outlined, its kind written at the bottom."""

    def __init__(self, rect: QRectF, area: str, kind: str, tip: str) -> None:
        super().__init__(rect)
        self.area, self.kind = area, kind
        self.setBrush(QBrush(COLOURS[area]))
        self.setPen(QPen(EDGES[area], 1.5))
        self.setZValue(SHADE_Z)
        self.setToolTip(tip)
        self.setAcceptedMouseButtons(Qt.MouseButton.NoButton)

    def paint(self, painter: QPainter, option, widget=None) -> None:  # noqa: ANN001
        super().paint(painter, option, widget)
        rect = self.rect()
        painter.fillRect(rect, QBrush(EDGES[self.area], Qt.BrushStyle.BDiagPattern))
        painter.setPen(EDGES[self.area])
        font = painter.font()
        font.setPointSizeF(7.5)
        painter.setFont(font)
        painter.drawText(rect.adjusted(3, 0, -2, -2), Qt.AlignmentFlag.AlignBottom, self.kind)


def summary(report: Report) -> str:
    """The message bar's line for a report; with no findings, the first check that could not run."""
    if not report.findings:
        skipped = [n for n in report.notes if "not checked" in n]
        more = f" (+{len(skipped) - 1} more)" if len(skipped) > 1 else ""
        return "No device or perception limit crossed" + (
            f"; but {skipped[0]}{more}" if skipped else ""
        )
    first = report.findings[0]
    more = len(report.findings) - 1
    tail = f" (+{more} more: hover the shading)" if more else ""
    return f"{len(report.findings)} limit(s) crossed: {first.describe()}{tail}"


class FindingsOverlay(QObject):
    """Checks the document after edits and shows the findings on the timeline view."""

    ready = Signal(object, int)  # Checked or HapticTimelineError, version

    def __init__(self, doc, view, messages, player) -> None:  # noqa: ANN001 - GUI objects
        super().__init__(view)
        self.doc, self.view, self.messages, self.player = doc, view, messages, player
        self.report: Report | None = None
        self.version = 0
        self._done = -1  # the version the shown report belongs to
        self.shades: list[FindingShade] = []
        self.traces: tuple[Trace, ...] = ()
        self.peaks: tuple[Peaks, ...] = ()
        self.rendered = RenderedLayer(view.scene())
        self._unrendered = ""  # the last rendering error said
        self._infos: dict[str, DeviceInfo] = {}
        self._pool = ThreadPoolExecutor(max_workers=1, thread_name_prefix="findings")
        self._timer = QTimer(self)
        self._timer.setSingleShot(True)
        self._timer.timeout.connect(self._start)
        self.ready.connect(self._show)
        doc.changed.connect(lambda _project: self.schedule())
        view.scene().sceneRectChanged.connect(lambda _rect: self._redraw())  # zoom, new lanes
        self.schedule()

    @property
    def settled(self) -> bool:
        """True when the shown findings belong to the document as it is."""
        return self.report is not None and not self._timer.isActive() and self._done == self.version

    def schedule(self) -> None:
        """Check again once edits pause."""
        self.version += 1
        self._timer.start(DELAY_MS)

    def show_rendered(self, on: bool) -> None:
        """Draw the device's output over the lanes (computed after the next check) or stop."""
        if on:
            self._unrendered = ""
            self.schedule()
        else:
            self.traces, self.peaks = (), ()
            self.rendered.clear()

    def hand_changed(self) -> None:
        """The transport's hand changed: what a knob's drive makes felt, and its rendering,
        depend on it."""
        self.schedule()

    def device_info(self) -> DeviceInfo:
        """What the player's device declares (asked once per device)."""
        name = self.player.device_name
        if name not in self._infos:
            with open_device(name) as device:
                self._infos[name] = device.info
        return self._infos[name]

    def _start(self) -> None:
        version, project = self.version, self.doc.project
        try:
            info = self.device_info()
        except HapticTimelineError as exc:
            self.ready.emit(exc, version)
            return
        if project.axis == "time" and project.duration * info.rate > MAX_LIVE_SAMPLES:
            self.ready.emit(HapticTimelineError(
                f"the design is too long to check while editing ({project.duration:.0f} s); "
                "run haptic-timeline check on it"), version)  # fmt: skip
            return
        future = self._pool.submit(_check, project, info, self.player.hand, self.rendered.shown)
        future.add_done_callback(lambda f: self.ready.emit(f.result(), version))

    def _show(self, result: Checked | HapticTimelineError, version: int) -> None:
        if version != self.version:
            return  # an edit came since: its own check follows
        self._done = version
        if isinstance(result, HapticTimelineError):
            text = f"Cannot check the design: {result}"
            if self.report is None or self.report.notes != (text,):
                self.messages.show_message(text, "error")
            self.report, self.traces, self.peaks = Report((), (text,)), (), ()
            self._draw(self.doc.project, self.report)
            return
        report = result.report
        changed = (
            self.report is None
            or _keys(self.report) != _keys(report)
            or self.report.notes != report.notes
        )
        self.report, self.traces, self.peaks = report, result.traces, result.peaks
        self._draw(self.doc.project, report)
        if changed:
            self.messages.show_message(summary(report), "finding" if report.findings else "info")
        if result.unrendered and result.unrendered != self._unrendered:
            self.messages.show_message(result.unrendered, "error")
        self._unrendered = result.unrendered

    def _redraw(self) -> None:
        if self.report is not None:
            self._draw(self.doc.project, self.report)

    def _draw(self, project: Project, report: Report) -> None:
        scene = self.view.scene()
        for shade in self.shades:
            scene.removeItem(shade)
        self.shades = []
        geometry = scene.lane_geometry
        terms = [track_kind(t.kind).term for t in project.tracks]
        for finding in report.findings:
            layer = LAYER_OF.get(finding.layer, finding.layer)
            lanes = [i for i, term in enumerate(terms) if term == layer] or range(len(terms))
            x0, x1 = geometry.x(finding.start), geometry.x(finding.stop)
            for lane in lanes:
                rect = QRectF(x0, geometry.lane_top(lane) + 1, max(x1 - x0, 2.0),
                              geometry.lane_height - 2)  # fmt: skip
                shade = FindingShade(rect, finding.area, finding.kind, finding.describe())
                scene.addItem(shade)
                self.shades.append(shade)
        self.rendered.draw(project, list(self.traces), list(self.peaks), geometry)

    def close(self) -> None:
        """Stop checking (the window is closing)."""
        self._timer.stop()
        self._pool.shutdown(wait=False, cancel_futures=True)


def _check(
    project: Project, info: DeviceInfo, hand: Hand, render: bool
) -> Checked | HapticTimelineError:
    """The findings with this hand on a knob and, if `render`, what the device will output."""
    try:
        report = check(project, info, hand=hand)
    except HapticTimelineError as exc:
        return exc
    if not render:
        return Checked(report)
    from timeline.limits.plot import traces

    try:
        drawn = tuple(traces(project, info, info.actuator, hand, "normal"))
        return Checked(report, drawn, tuple(peaks_of(t) for t in drawn))
    except HapticTimelineError as exc:  # e.g. too short to render: the findings still stand
        return Checked(report, unrendered=f"Cannot show the rendered output: {exc}")


def _keys(report: Report) -> list[tuple[str, float, float]]:
    return [(f.kind, round(f.start, 6), round(f.stop, 6)) for f in report.findings]
