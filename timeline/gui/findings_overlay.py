"""Findings on the lanes: where the design crosses a device or perception limit, kept current.

After each edit (debounced) the project is checked in a worker thread against the player's
device (timeline.limits.check); the result shades the spans on the lanes whose layer it is
about (device limits orange, perception purple; hover for the sentence) and puts one line in
the message bar when the findings change. While View > Show rendered by device is on, the same
worker also computes what the device will output (rendered_overlay) and the lanes show it.
"""

from __future__ import annotations

import math
import threading
from collections import Counter
from collections.abc import Callable
from concurrent.futures import Future, ThreadPoolExecutor
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from PySide6.QtCore import QObject, QPointF, QRectF, Qt, QTimer, Signal
from PySide6.QtGui import QBrush, QColor, QImage, QPainter, QPen
from PySide6.QtWidgets import QGraphicsItem

from timeline.errors import HapticTimelineError
from timeline.model import Project
from timeline.plugins.device_protocol import DeviceInfo, Hand, open_device
from timeline.plugins.track_kinds import track_kind

from .clip_layer import runs
from .first_paint import after_first_paint
from .geometry import Geometry
from .lane_scale import visible_lanes
from .rendered_overlay import RenderedLayer, peaks_of
from .trace_peaks import Peaks

if TYPE_CHECKING:  # scipy loads with the first check, after the window's first paint
    from timeline.limits.check import Report
    from timeline.limits.findings import Finding
    from timeline.limits.rendered import Trace

DELAY_MS = 250  # after the last edit
MAX_LIVE_SAMPLES = 6_000_000  # 10 minutes at 10 kHz: longer designs are checked by the CLI
COLOURS = {"device": QColor(230, 126, 34, 60), "perception": QColor(142, 68, 173, 50)}
EDGES = {"device": QColor(211, 84, 0), "perception": QColor(110, 44, 140)}
LAYER_OF = {"amplitude": "d", "frequency": "d"}  # a sub-JND measure's layer
SHADE_Z = 15  # above clips, below the playhead and cursor
LABEL_PX = 30.0  # spans this wide are drawn one by one with their kind; narrower ones merged


class CheckCancelled(Exception):
    """Raised inside a running check once a newer edit has made it stale (editor-internal)."""


@dataclass(frozen=True)
class Checked:
    """What the worker found: the report and, when asked for, the rendered traces."""

    report: Report
    traces: tuple[Trace, ...] = ()
    peaks: tuple[Peaks, ...] = ()  # each trace's, ready to draw at any zoom
    unrendered: str = ""  # why the traces could not be computed, when they were asked for


@dataclass(frozen=True)
class Shade:
    """One finding's span on one lane, as the shading layer draws it."""

    finding: Finding
    lane: int
    geometry: Geometry

    @property
    def area(self) -> str:
        return self.finding.area

    @property
    def kind(self) -> str:
        return self.finding.kind

    def rect(self) -> QRectF:
        """Its scene rectangle at the current zoom (at least 2 pixels wide)."""
        g = self.geometry
        x0, x1 = g.x(self.finding.start), g.x(self.finding.stop)
        return QRectF(x0, g.lane_top(self.lane) + 1, max(x1 - x0, 2.0), g.lane_height - 2)

    def toolTip(self) -> str:  # noqa: N802 - as the item's it replaces
        return self.finding.describe()


class _Group:
    """Findings of one area shown on the same lanes, as arrays for the visible range."""

    def __init__(self, area: str, lanes: tuple[int, ...], findings: list[Finding]) -> None:
        self.area, self.lanes, self.findings = area, lanes, findings
        self.starts = np.array([f.start for f in findings], dtype=np.float64)
        self.stops = np.array([f.stop for f in findings], dtype=np.float64)


class ShadeLayer(QGraphicsItem):
    """Every finding's shading, painted for the exposed part only (one item, whatever the count).

    A span is hatched and outlined on each lane of its layer, its kind written at the bottom; at
    a zoom where spans are narrower than LABEL_PX they are merged into runs of pixels, so 1,378
    findings on 25 lanes cost a few calls per visible lane, and a zoom rebuilds nothing.
    """

    def __init__(self, geometry: Geometry) -> None:
        super().__init__()
        self.g = geometry
        self.groups: list[_Group] = []
        self._version = 0  # of the groups, for the strips kept
        self._strips: dict[tuple[int, int, int], _Strip] = {}  # (group, left, right) -> strip
        self._strips_of: tuple[object, ...] = ()  # the groups' version, zoom and lane height
        self._rect = QRectF()
        self.setZValue(SHADE_Z)
        self.setAcceptedMouseButtons(Qt.MouseButton.NoButton)
        self.setFlag(QGraphicsItem.GraphicsItemFlag.ItemUsesExtendedStyleOption)

    def show(self, project: Project, findings: tuple[Finding, ...]) -> None:
        """Shade these findings on the project's lanes."""
        terms = [track_kind(t.kind).term for t in project.tracks]
        grouped: dict[tuple[str, tuple[int, ...]], list[Finding]] = {}
        for finding in findings:
            layer = LAYER_OF.get(finding.layer, finding.layer)
            lanes = tuple(i for i, term in enumerate(terms) if term == layer) or tuple(
                range(len(terms))
            )
            grouped.setdefault((finding.area, lanes), []).append(finding)
        self.groups = [_Group(area, lanes, f) for (area, lanes), f in grouped.items()]
        self._version += 1
        self.update()

    def shades(self) -> list[Shade]:
        """One per finding per lane it is shown on."""
        return [
            Shade(f, lane, self.g)
            for grp in self.groups
            for f in grp.findings
            for lane in grp.lanes
        ]

    def resize(self, rect: QRectF) -> None:
        """Cover the scene rectangle."""
        if rect != self._rect:
            self.prepareGeometryChange()
            self._rect = QRectF(rect)

    def boundingRect(self) -> QRectF:  # noqa: N802 - Qt's name
        return self._rect

    def tip(self, pos: QPointF) -> str:
        """The sentence of the finding under a scene position ("" if none)."""
        lane = self.g.lane_at(pos.y())
        u = self.g.u(pos.x())
        slack = self.g.u(1.0)  # a span drawn 2 pixels wide is hovered that wide
        for grp in self.groups:
            if lane in grp.lanes:
                hit = np.flatnonzero((grp.starts <= u + slack) & (grp.stops >= u - slack))
                if hit.size:
                    return grp.findings[int(hit[0])].describe()
        return ""

    def paint(self, painter: QPainter, option, widget=None) -> None:  # noqa: ANN001
        exposed = option.exposedRect
        g = self.g
        left = math.floor(exposed.left()) - 2
        right = max(math.ceil(exposed.right()) + 2, left + 1)
        lanes_shown = visible_lanes(g, 1 << 30, exposed)
        font = painter.font()
        font.setPointSizeF(7.5)
        painter.setFont(font)
        painter.setRenderHint(QPainter.RenderHint.Antialiasing, False)  # rectangles on pixels
        for index, grp in enumerate(self.groups):
            lanes = [lane for lane in grp.lanes if lane in lanes_shown]
            if not lanes:
                continue
            strips = [self._strip(index, grp, a, b) for a, b in _strip_columns(left, right)]
            labels = dict.fromkeys(label for strip in strips for label in strip.labels)
            painter.setPen(EDGES[grp.area])
            for lane in lanes:
                top = g.lane_top(lane)
                for strip in strips:
                    strip.draw(painter, top)
                for a, b, kind in labels:
                    painter.drawText(
                        QRectF(a, top + 1, b - a, g.lane_height - 2).adjusted(3, 0, -2, -2),
                        Qt.AlignmentFlag.AlignBottom,
                        kind,
                    )

    def _strip(self, index: int, grp: _Group, left: int, right: int) -> _Strip:
        """The group's shading on scene columns left..right of a lane (kept while the findings,
        the zoom and the lane height stay)."""
        g = self.g
        state = (self._version, g.px_per_unit, g.lane_height)
        if state != self._strips_of or len(self._strips) > MAX_STRIPS:
            self._strips_of = state
            self._strips.clear()
        kept = self._strips.get((index, left, right))
        if kept is not None:
            return kept
        u0, u1 = g.u(left), g.u(right)
        seen = np.flatnonzero((grp.starts <= u1) & (grp.stops >= u0))
        x0 = grp.starts[seen] * g.px_per_unit
        x1 = np.maximum(grp.stops[seen] * g.px_per_unit, x0 + 2.0)
        wide = (x1 - x0) >= LABEL_PX
        kinds = [grp.findings[i].kind for i in seen[wide].tolist()]
        labels = list(zip(x0[wide].tolist(), x1[wide].tolist(), kinds, strict=True))
        spans = runs(x0[~wide], x1[~wide]) + [(a, b) for a, b, _ in labels]
        columns = _shaded_columns(x0, x1, left, right)
        strip = _Strip(left, right, grp.area, spans, labels, columns, g)
        self._strips[(index, left, right)] = strip
        return strip


STRIP_PX = 2048  # the shading is painted in strips at most this wide
CHUNK_PX = 256  # a narrow repaint's strips: columns at multiples of this, kept for the next


def _strip_columns(left: int, right: int) -> list[tuple[int, int]]:
    """The strips' columns [a, b) for an exposed range: its own for a wide one (a paint at a
    new zoom), fixed chunks for a narrow one, so that the next repaint nearby (a drag move's:
    the clip and the snap line) finds them painted."""
    if right - left > 2 * CHUNK_PX:
        return [(a, min(right, a + STRIP_PX)) for a in range(left, right, STRIP_PX)]
    first = left // CHUNK_PX * CHUNK_PX
    return [(a, a + CHUNK_PX) for a in range(first, right, CHUNK_PX)]


MAX_STRIPS = 64  # strips kept (scrolling at one zoom paints new ones)


class _Strip:
    """One group's shading on some columns of a lane, painted once into an image and drawn on
    each of its lanes: the spans are hatched and outlined as on the lane itself, in one image
    per phase of the 8-pixel hatch (lane tops 76 pixels apart alternate it)."""

    def __init__(
        self,
        left: int,
        right: int,
        area: str,
        spans: list[tuple[float, float]],
        labels: list[tuple[float, float, str]],
        columns: list[tuple[int, int]],
        geometry: Geometry,
    ) -> None:
        self.left, self.right, self.area = left, right, area
        self.spans, self.labels, self.g = spans, labels, geometry
        self.columns = columns  # the runs of its columns `draw` draws
        self._images: dict[float, QImage] = {}

    def image(self, top: float) -> QImage:
        """The picture for a lane whose top is at this scene y."""
        phase = top % 8
        if phase not in self._images:
            self._images[phase] = self._paint(top)
        return self._images[phase]

    def draw(self, painter: QPainter, top: float) -> None:
        """Draw the shading on the lane whose top is at this scene y: only the columns its spans
        touch (blending the transparent rest changes no pixel but costs as much per pixel)."""
        if not self.columns:
            return
        image = self.image(top)
        height = image.height()
        for a, b in self.columns:
            target = QRectF(self.left + a, top, b - a, height)
            painter.drawImage(target, image, QRectF(a, 0, b - a, height))

    def _paint(self, top: float) -> QImage:
        g, left, right = self.g, self.left, self.right
        image = QImage(right - left, g.lane_height, QImage.Format.Format_ARGB32_Premultiplied)
        image.fill(0)
        painter = QPainter(image)
        painter.translate(-left, -top)  # scene coordinates: the hatch keeps its phase
        rects = [QRectF(a, top + 1, b - a, g.lane_height - 2) for a, b in self.spans]
        edge = EDGES[self.area]
        painter.setPen(QPen(edge, 1))  # 1 px: a wider pen is stroked, 10x slower
        painter.setBrush(QBrush(COLOURS[self.area]))
        painter.drawRects(rects)
        painter.setPen(Qt.PenStyle.NoPen)
        painter.setBrush(QBrush(edge, Qt.BrushStyle.BDiagPattern))
        painter.drawRects(rects)
        painter.end()
        return image


def _shaded_columns(x0: np.ndarray, x1: np.ndarray, left: int, right: int) -> list[tuple[int, int]]:
    """The runs [a, b) of a strip's columns (from its left) that rectangles from x0 to x1 can
    touch (a pixel of outline each side), runs less than GAP_PX apart joined (a drawing call
    costs about as much as blending that many columns)."""
    if x0.size == 0:
        return []
    starts = np.clip(np.floor(x0) - 1 - left, 0, right - left)
    stops = np.clip(np.ceil(x1) + 2 - left, 0, right - left)
    order = np.argsort(starts, kind="stable")
    a, b = starts[order], np.maximum.accumulate(stops[order])
    breaks = np.flatnonzero(a[1:] > b[:-1] + GAP_PX) + 1
    firsts = np.concatenate(([0], breaks))
    lasts = np.concatenate((breaks - 1, [a.size - 1]))
    return [(int(x), int(y)) for x, y in zip(a[firsts], b[lasts], strict=True) if y > x]


# shaded columns this close are drawn in one call: a drawImage costs ~2.7 us and blending a
# column of a 76 px lane ~27 ns more (timed alone, offscreen), so a call is worth 100 columns
GAP_PX = 100


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
    """Checks the document after edits and shows the findings on the timeline view.

    One check runs at a time: an edit makes the running check stale and stops it at its next
    step (limits.check's `interrupt`), a queued one is dropped, and a drag starts no check until
    the mouse lets go, so a drag with pauses leaves no pile of checks behind it. The first check
    waits for the window's first paint (`painted`: made after it, the overlay starts checking at
    once).
    """

    ready = Signal(object, int)  # Checked or HapticTimelineError, version

    def __init__(self, doc, view, messages, player, painted: bool = False) -> None:  # noqa: ANN001
        super().__init__(view)
        self.doc, self.view, self.messages, self.player = doc, view, messages, player
        self.report: Report | None = None
        self.version = 0
        self._done = -1  # the version the shown report belongs to
        self.layer = ShadeLayer(view.scene().lane_geometry)
        view.scene().addItem(self.layer)
        view.scene().tip_sources.append(self.layer.tip)
        self.traces: tuple[Trace, ...] = ()
        self.peaks: tuple[Peaks, ...] = ()
        self.rendered = RenderedLayer(view.scene())
        self._unrendered = ""  # the last rendering error said
        self._infos: dict[str, DeviceInfo] = {}
        self._pool = ThreadPoolExecutor(max_workers=1, thread_name_prefix="findings")
        self._future: Future | None = None  # the latest check, queued or running
        self._stop = threading.Event()  # set to stop the latest check
        self._lock = threading.Lock()
        self.counts: Counter[str] = Counter()  # started, finished, cancelled (for the bench)
        self._running: dict[int, threading.Event] = {}  # version -> stop, of started checks
        self._closed = False
        self._drawn: object = None  # the report and lane terms the shading was grouped for
        self._timer = QTimer(self)
        self._timer.setSingleShot(True)
        self._timer.timeout.connect(self._start)
        self.ready.connect(self._show)
        self._held = False  # an edit waits for the drag that made it to end
        doc.changed.connect(lambda _project: self.schedule())
        view.gesture_finished.connect(self._let_go)
        view.scene().sceneRectChanged.connect(lambda _rect: self._redraw())  # zoom, new lanes
        if painted:
            self.schedule()
        else:
            after_first_paint(view.viewport(), self._first_check)

    @property
    def shades(self) -> list[Shade]:
        """The shading: one per finding per lane it is shown on."""
        return self.layer.shades()

    @property
    def settled(self) -> bool:
        """True when the shown findings belong to the document as it is."""
        return self.report is not None and not self._timer.isActive() and self._done == self.version

    @property
    def busy(self) -> bool:
        """True while a check is queued or running."""
        return self._future is not None and not self._future.done()

    def stale_running(self) -> list[int]:
        """Versions of checks still running though an edit has made them stale."""
        with self._lock:
            return [v for v in self._running if v != self.version]

    def _first_check(self) -> None:
        if self.report is None and not self._timer.isActive():
            self.schedule()

    def schedule(self) -> None:
        """Check again once edits pause; the check under way (now stale) stops. An edit made
        while the mouse holds a drag is checked once it lets go: a pause in a drag starts none."""
        self.version += 1
        self._cancel()
        self._held = self.view.gesture is not None
        if not self._closed and not self._held:  # an edit as the window closes starts no check
            self._timer.start(DELAY_MS)

    def _let_go(self) -> None:
        """A drag ended: check what it left."""
        if self._held and not self._closed:
            self._held = False
            self._timer.start(DELAY_MS)

    def _cancel(self) -> None:
        """Drop the latest check if it is queued, or tell it to stop if it runs."""
        if self._future is not None and not self._future.cancel():
            self._stop.set()
        self._future = None

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
        if self._closed:  # a timer that fired as the window closed
            return
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
        self._cancel()
        self._stop = stop = threading.Event()
        future = self._pool.submit(
            self._run, project, info, self.player.hand, self.rendered.shown, stop, version
        )
        self._future = future
        future.add_done_callback(lambda f: self._finished(f, version))

    def _run(
        self,
        project: Project,
        info: DeviceInfo,
        hand: Hand,
        render: bool,
        stop: threading.Event,
        version: int,
    ) -> Checked | HapticTimelineError | None:
        """Worker thread: the check, or None when it was stopped as stale."""

        def interrupt() -> None:
            if stop.is_set():
                raise CheckCancelled

        with self._lock:
            self.counts["started"] += 1
            self._running[version] = stop
        try:
            result = _check(project, info, hand, render, interrupt)
        except CheckCancelled:
            self._count("cancelled")
            return None
        finally:
            with self._lock:
                del self._running[version]
        self._count("finished")
        return result

    def _count(self, what: str) -> None:
        with self._lock:
            self.counts[what] += 1

    def _finished(self, future: Future, version: int) -> None:
        """Any thread: hand a check's result to the GUI thread (nothing once closed or stale)."""
        if future.cancelled():  # dropped before it started
            self._count("cancelled")
            return
        result = future.result()
        if result is not None and not self._closed:
            self.ready.emit(result, version)

    def _show(self, result: Checked | HapticTimelineError, version: int) -> None:
        if version != self.version:
            return  # an edit came since: its own check follows
        self._done = version
        if isinstance(result, HapticTimelineError):
            from timeline.limits.check import Report

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
            self.messages.show_routine(summary(report), "finding" if report.findings else "info")
        if result.unrendered and result.unrendered != self._unrendered:
            self.messages.show_message(result.unrendered, "error")
        self._unrendered = result.unrendered

    def _redraw(self) -> None:
        self.layer.resize(self.view.scene().sceneRect())
        if self.report is not None:
            self._draw(self.doc.project, self.report)

    def _draw(self, project: Project, report: Report) -> None:
        self.layer.resize(self.view.scene().sceneRect())
        terms = tuple(track_kind(t.kind).term for t in project.tracks)
        if self._drawn != (id(report), terms):  # a zoom regroups nothing
            self._drawn = (id(report), terms)
            self.layer.show(project, report.findings)
        if self.traces or self.rendered.items:
            geometry = self.view.scene().lane_geometry
            self.rendered.draw(project, list(self.traces), list(self.peaks), geometry)

    def close(self) -> None:
        """Stop checking (the window is closing): the queued check is dropped, the running one
        stopped, and nothing is said about either."""
        self._closed = True
        self._timer.stop()
        self._cancel()
        self._pool.shutdown(wait=False, cancel_futures=True)


def _check(
    project: Project,
    info: DeviceInfo,
    hand: Hand,
    render: bool,
    interrupt: Callable[[], None],
) -> Checked | HapticTimelineError:
    """The findings with this hand on a knob and, if `render`, what the device will output;
    `interrupt` raises CheckCancelled between steps once the check is stale."""
    from timeline.limits.check import check  # scipy.signal: not on the way to the first paint

    try:
        report = check(project, info, hand=hand, interrupt=interrupt)
    except HapticTimelineError as exc:
        return exc
    if not render:
        return Checked(report)
    from timeline.limits.plot import traces

    interrupt()
    try:
        drawn = tuple(traces(project, info, info.actuator, hand, "normal"))
        return Checked(report, drawn, tuple(peaks_of(t) for t in drawn))
    except HapticTimelineError as exc:  # e.g. too short to render: the findings still stand
        return Checked(report, unrendered=f"Cannot show the rendered output: {exc}")


def _keys(report: Report) -> list[tuple[str, float, float]]:
    return [(f.kind, round(f.start, 6), round(f.stop, 6)) for f in report.findings]
