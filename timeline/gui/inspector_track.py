"""The inspector's track page: the selected track's name, gain and full scale (what a tile value
of 1 means on it, in the kind's display unit); each change is one undo step."""

from __future__ import annotations

from PySide6.QtWidgets import QFormLayout, QLabel, QLineEdit, QWidget

from timeline import edits
from timeline.model import Track
from timeline.plugins.track_kinds import track_kind

from . import quiet
from .document import Document
from .inspector_fields import NumberField


class TrackPage(QWidget):
    """Name, gain and full scale of the selected track."""

    def __init__(self, doc: Document) -> None:
        super().__init__()
        self.doc = doc
        self.title = QLabel()
        self.name = QLineEdit()
        self.name.setToolTip("the track's name; type and press Enter")
        self.name.editingFinished.connect(self._rename)
        self.gain = NumberField(self._set_gain, 4, prefix="x", bounds=(-100.0, 100.0), tip="gain")
        # 6 decimals: a light damping lane's 0.001745 mNm*s/deg (1e-4 N*m*s/rad) shows
        self.full_scale = NumberField(self._set_full_scale, 6, bounds=(-1e9, 1e9))
        form = QFormLayout(self)
        form.setContentsMargins(0, 0, 0, 0)
        form.addRow(self.title)
        form.addRow("name", self.name)
        form.addRow("gain", self.gain)
        form.addRow("full scale", self.full_scale)

    def track(self) -> Track | None:
        tracks = self.doc.project.tracks
        return next((t for t in tracks if t.id == self.doc.selected_track), None)

    def refresh(self) -> None:
        track = self.track()
        if track is None:
            return
        kind = track_kind(track.kind)
        full = kind.full_scale if track.full_scale is None else track.full_scale
        quiet.set_text(self.title, f"<b>track</b> · {kind.label}")
        if not self.name.hasFocus():
            quiet.set_text(self.name, track.name)
        self.gain.show_value(track.gain)
        quiet.set_format(self.full_scale, suffix=f" {kind.display_unit}")
        self.full_scale.setToolTip(
            f"what a tile value of 1 means on this track, in {kind.display_unit} (the kind's is "
            f"{kind.full_scale * kind.display_scale:g}); type and press Enter"
        )
        self.full_scale.show_value(full * kind.display_scale)

    def _rename(self) -> None:
        track, name = self.track(), self.name.text().strip()
        if track is None or not name or name == track.name:
            return
        self.doc.apply(f"rename track {track.name} to {name}", edits.set_track, track.id, name=name)
        self.refresh()

    def _set_gain(self, gain: float) -> None:
        track = self.track()
        if track is not None:
            self.doc.apply(f"set gain of {track.name} to x{gain:g}", edits.set_track, track.id,
                           gain=gain)  # fmt: skip
            self.refresh()

    def _set_full_scale(self, shown: float) -> None:
        track = self.track()
        if track is None:
            return
        kind = track_kind(track.kind)
        label = f"set full scale of {track.name} to {shown:g} {kind.display_unit}"
        self.doc.apply(label, edits.set_track, track.id, full_scale=shown / kind.display_scale)
        self.refresh()
