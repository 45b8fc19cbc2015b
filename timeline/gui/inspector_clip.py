"""The inspector's clip page: the selected clip's start, length, gain (x and dB), fades, stretch
and mirror line, typed exactly in the project's display units; each change is one undo step
through the same edits as the drags, so it is felt at once while playing."""

from __future__ import annotations

import math
from dataclasses import fields

from PySide6.QtWidgets import QComboBox, QFormLayout, QLabel, QWidget

from timeline import edits
from timeline.edits.vibration import with_emphasis
from timeline.model import FADE_SHAPES, Clip, Project, Track

from . import quiet
from .document import Document
from .geometry import axis_text
from .inspector_fields import AXIS_DECIMALS, NumberField, axis_suffix, axis_value, pair, shown_axis
from .lane_scale import full_scale_text

MIN_DB = -120.0
_NOT_START = tuple(f.name for f in fields(Clip) if f.name != "start")


class ClipPage(QWidget):
    """Exact values of the first selected clip."""

    def __init__(self, doc: Document) -> None:
        super().__init__()
        self.doc = doc
        self.title = QLabel()
        self.start = NumberField(self._set_start, tip="where the clip starts")
        self.length = NumberField(self._set_length, bounds=(0.0, 1e9), tip="trim the clip's end")
        self.gain = NumberField(self._set_gain, 4, prefix="x", bounds=(-1e3, 1e3), tip="gain")
        self.db = NumberField(self._set_db, 2, " dB", bounds=(MIN_DB, 60.0), tip="gain in dB")
        self.fade_in = NumberField(lambda v: self._set_fade("in", v), bounds=(0.0, 1e9))
        self.fade_out = NumberField(lambda v: self._set_fade("out", v), bounds=(0.0, 1e9))
        self.shape_in, self.shape_out = self._shape_box("in"), self._shape_box("out")
        self.stretch = NumberField(self._set_stretch, 4, prefix="x", bounds=(1e-4, 1e4))
        self.stretch.setToolTip("stretch factor (squeeze resamples, repeat loops); type and Enter")
        self.mirror = NumberField(self._set_mirror, 3, bounds=(-10.0, 10.0))
        self._axis: str | None = None  # the axis the fields' formats are set for
        self._rest: tuple[object, ...] = ()  # all the fields show but the start, as shown
        form = QFormLayout(self)
        form.setContentsMargins(0, 0, 0, 0)
        form.addRow(self.title)
        form.addRow("start", self.start)
        form.addRow("length", self.length)
        form.addRow("gain", pair(self.gain, self.db))
        form.addRow("fade in", pair(self.fade_in, self.shape_in))
        form.addRow("fade out", pair(self.fade_out, self.shape_out))
        form.addRow("stretch", self.stretch)
        form.addRow("mirror line", self.mirror)

    def _shape_box(self, which: str) -> QComboBox:
        box = QComboBox()
        box.addItems(FADE_SHAPES)
        box.setSizeAdjustPolicy(QComboBox.SizeAdjustPolicy.AdjustToMinimumContentsLengthWithIcon)
        box.setMinimumContentsLength(6)  # "equal-power" elided rather than widening the pane
        box.setToolTip(f"the fade-{which}'s shape")
        box.activated.connect(lambda i: self._set_fade(which, None, FADE_SHAPES[i]))
        return box

    def found(self) -> tuple[Track, Clip] | None:
        """The clip shown: the first selected one."""
        project = self.doc.project
        if not self.doc.selected_clips:
            return None
        return project.find_clip(self.doc.selected_clips[0])

    def refresh(self) -> None:
        """Show the clip's current values (in s, or degrees in a position project); a drag
        changes one or two of them, so only what differs from what is shown is set."""
        found = self.found()
        if found is None:
            return
        track, clip = found
        project = self.doc.project
        axis = project.axis
        name = project.tile(clip.tile_id).name
        more = len(self.doc.selected_clips) - 1
        rest = (*(getattr(clip, f) for f in _NOT_START), track.name, track.kind, track.full_scale,
                name, more, axis)  # fmt: skip
        if rest == self._rest:  # a move along the track: only the start changed
            self.start.show_value(shown_axis(clip.start, axis))
            return
        self._rest = rest
        extra = f" (+{more})" if more else ""
        # one short line: a wrapping label would squeeze the fields in the scroll area
        quiet.set_text(self.title, f"<b>clip</b> · {name}{extra}")
        _set_tip(self.title, f"a clip of {name} on {track.name}")
        if axis != self._axis:
            self._axis = axis
            for box in (self.start, self.length, self.fade_in, self.fade_out):
                quiet.set_format(box, decimals=AXIS_DECIMALS[axis], suffix=axis_suffix(axis))
            quiet.set_format(self.start, minimum=0.0 if axis == "time" else -1e9)
        self.start.show_value(shown_axis(clip.start, axis))
        self.length.show_value(shown_axis(clip.duration, axis))
        self.gain.show_value(clip.gain)
        self.db.show_value(20 * math.log10(abs(clip.gain)) if clip.gain else MIN_DB)
        self.fade_in.show_value(shown_axis(clip.fade_in.length, axis))
        self.fade_out.show_value(shown_axis(clip.fade_out.length, axis))
        for box, shape in (
            (self.shape_in, clip.fade_in.shape),
            (self.shape_out, clip.fade_out.shape),
        ):
            if box.currentText() != shape:
                box.setCurrentText(shape)
        self.stretch.show_value(clip.stretch)
        quiet.set_format(self.stretch, suffix=" (loops)" if clip.stretch_mode == "repeat" else "")
        self.mirror.show_value(clip.pivot)
        _set_tip(
            self.mirror,
            "the horizontal line amplitude drags and inversion turn about, in the clip's values "
            f"(1 = full scale: {full_scale_text(track, 1.0)} on {track.name}); type and Enter",
        )

    # --- edits (one undo step each) --------------------------------------------------------

    def _apply(self, what: str, shown: str, edit, *args) -> None:
        found = self.found()
        if found is None:
            return
        name = self.doc.project.tile(found[1].tile_id).name
        self.doc.apply(f"set {what} of '{name}' to {shown}", edit, found[1].id, *args)
        self._rest = ()  # every field shown again: a refused value goes back to the clip's
        self.refresh()

    def _set_start(self, shown: float) -> None:
        axis = self.doc.project.axis
        self._apply("start", axis_text(axis_value(shown, axis), axis), _start_at,
                    axis_value(shown, axis))  # fmt: skip

    def _set_length(self, shown: float) -> None:
        axis = self.doc.project.axis
        length = axis_value(shown, axis)
        self._apply("length", axis_text(length, axis), _length_to, length)

    def _set_gain(self, gain: float) -> None:
        self._apply("gain", f"x{gain:g}", edits.set_clip_gain, gain)

    def _set_db(self, db: float) -> None:
        found = self.found()
        sign = -1.0 if found is not None and found[1].gain < 0 else 1.0
        gain = 0.0 if db <= MIN_DB else sign * 10.0 ** (db / 20.0)
        self._apply("gain", f"{db:g} dB", edits.set_clip_gain, gain)

    def _set_fade(self, which: str, shown: float | None, shape: str | None = None) -> None:
        found = self.found()
        if found is None:
            return
        axis = self.doc.project.axis
        fade = found[1].fade_in if which == "in" else found[1].fade_out
        length = fade.length if shown is None else axis_value(shown, axis)
        shape = shape or fade.shape
        text = f"{axis_text(length, axis)} {shape}"
        self._apply(f"fade {which}", text, edits.set_fade, which, length, shape)

    def _set_stretch(self, factor: float) -> None:
        self._apply("stretch", f"x{factor:g}", _stretch_to, factor)

    def _set_mirror(self, value: float) -> None:
        self._apply("mirror line", f"{value:g}", edits.set_pivot, value)


def _set_tip(widget: QWidget, text: str) -> None:
    """Set a tooltip where it differs (setting one sends the widget an event even when equal)."""
    if widget.toolTip() != text:
        widget.setToolTip(text)


def _start_at(project: Project, clip_id: str, start: float) -> Project:
    """Move a clip to a start, a vibration design's emphasis along (as a drag moves them)."""
    _, clip = project.find_clip(clip_id)
    others = [c for c in with_emphasis(project, [clip_id]) if c != clip_id]
    project = edits.move_clip(project, clip_id, start)
    return edits.shift_clips(project, others, start - clip.start)


def _length_to(project: Project, clip_id: str, length: float) -> Project:
    """Trim a clip's end so it lasts `length` (content stays in place)."""
    _, clip = project.find_clip(clip_id)
    return edits.trim_clip(project, clip_id, end=clip.start + length)


def _stretch_to(project: Project, clip_id: str, factor: float) -> Project:
    """Give a clip exactly this stretch factor (its fades kept inside it, its start kept)."""
    _, clip = project.find_clip(clip_id)
    project = edits.stretch_clip(project, clip_id, factor / clip.stretch)
    return edits.set_clip(project, clip_id, stretch=factor)
