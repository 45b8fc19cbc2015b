"""File > Import sound as haptic: a sound analysed into an editable design, its settings panel.

The panel (a dock beside the timeline) holds every analysis setting, starting at its default.
Importing analyses the sound off the GUI thread; when done, the design goes on a drive track
(the selected clip's or the lane under the pointer, if a drive lane, else the first) as envelope
breakpoints and emphasis, and the sound itself on a new audio track at the same time: one undo
step. Like any import, the new clips move later together to the first gap where they cover no
clip already there. Dropping sound files with Alt held does the same at the drop point.

The panel is live: a setting changed (after a pause of LIVE_DELAY_MS) re-analyses the sound of
the selected converted design, or else of the design imported last, and replaces that design
and its emphasis clips with the new analysis, as one undo step; every other clip stays as the
designer left it.
"""

from __future__ import annotations

from collections.abc import Callable
from functools import cache
from pathlib import Path
from typing import TYPE_CHECKING

from PySide6.QtCore import QEvent, QObject, Qt, QTimer
from PySide6.QtGui import QDropEvent
from PySide6.QtWidgets import QDockWidget, QMenu, QWidget

from timeline.edits.placement import into_gap
from timeline.errors import HapticTimelineError, SettingsError
from timeline.gui.file_jobs import FileJob

if TYPE_CHECKING:  # the analysis (numba) loads with the first sound converted, not at start-up
    from timeline.analysis import AnalysisSettings
    from timeline.analysis.staging import Staging
    from timeline.files.convert import ConvertedSound
    from timeline.gui.main_window import MainWindow

    from .analysis_panel import AnalysisPanel

SOUND_EXTENSIONS = "*.wav *.flac *.ogg *.aif *.aiff *.mp3 *.opus"
DROP_MODIFIER = Qt.KeyboardModifier.AltModifier
LIVE_DELAY_MS = 300  # a pause in changing settings after which the design is re-analysed


@cache
def _staging() -> Staging:
    """The level designs take, as `convert` stages them: for the default device (sim)."""
    from timeline.limits.staging import staging_for
    from timeline.plugins.device_protocol import open_device

    with open_device("sim") as device:
        return staging_for(device.info)


def _analyse(path: Path, settings: AnalysisSettings, progress) -> ConvertedSound:  # noqa: ANN001
    """Worker thread: a sound file's analysis at the default device's level, placed nowhere."""
    from timeline.files.convert import analyse_sound_file

    return analyse_sound_file(path, settings, progress=progress, staging=_staging())


def _reanalyse(path: Path, settings: AnalysisSettings, progress) -> ConvertedSound:  # noqa: ANN001
    """Worker thread: the sound analysed again, without reading it for an audio track."""
    from timeline.files.convert import analyse_sound_file

    return analyse_sound_file(
        path, settings, keep_sound=False, progress=progress, staging=_staging()
    )


class _SettingsDock(QDockWidget):
    """A dock that builds its widget the first time it is shown (the analysis panel's 29 fields
    cost ~15 ms, kept off the editor's launch while the dock is hidden)."""

    def __init__(self, title: str, parent: QWidget, build: Callable[[], object]) -> None:
        super().__init__(title, parent)
        self._build = build

    def setVisible(self, visible: bool) -> None:  # noqa: N802 - Qt's name
        if visible:
            self._build()
        super().setVisible(visible)


class SoundImport(QObject):
    """The editor's sound-to-haptic command: menu actions, the settings dock and the jobs."""

    def __init__(self, window: MainWindow) -> None:
        super().__init__(window)
        self.window = window
        self._panel: AnalysisPanel | None = None
        self.dock = _SettingsDock("Sound analysis", window, lambda: self.panel)
        self.dock.setObjectName("soundAnalysisDock")
        window.addDockWidget(Qt.DockWidgetArea.RightDockWidgetArea, self.dock)
        self.dock.hide()
        self._drop_modifiers = Qt.KeyboardModifier.NoModifier
        window.view.viewport().installEventFilter(self)
        self.sounds: dict[str, Path] = {}  # the sounds imported as haptic, by their file name
        self.last_sound = ""  # the file name of the sound imported last
        self._generation = 0  # the latest re-analysis; older ones finishing later are dropped
        self.live = QTimer(self)
        self.live.setSingleShot(True)
        self.live.setInterval(LIVE_DELAY_MS)
        self.live.timeout.connect(self.reanalyse)

    @property
    def panel(self) -> AnalysisPanel:
        """The settings panel in the dock, built when first needed."""
        if self._panel is None:
            from .analysis_panel import AnalysisPanel  # with the dock first shown

            self._panel = AnalysisPanel()
            self._panel.restore_defaults()
            self._panel.changed.connect(self.live.start)  # a changed setting re-runs the analysis
            self.dock.setWidget(self._panel)
        return self._panel

    def eventFilter(self, watched: QObject, event: QEvent) -> bool:  # noqa: N802 - Qt's name
        """Note the keys held when files are dropped on the lanes (the view handles the drop)."""
        if isinstance(event, QDropEvent):
            self._drop_modifiers = event.modifiers()
        return False

    def add_actions(self, menu: QMenu) -> None:
        """File menu entries: import a sound as a haptic design, show the settings panel."""
        act = self.window._action(menu, "Import sound as &haptic…", self.import_dialog,
                                  "Ctrl+Shift+H",
                                  "Analyse a sound into an editable haptic design")  # fmt: skip
        self.import_action = act
        toggle = self.dock.toggleViewAction()
        toggle.setText("Sound &analysis settings")
        menu.addAction(toggle)

    def wants_drop(self) -> bool:
        """Whether the files being dropped should be imported as haptics (Alt held)."""
        held, self._drop_modifiers = self._drop_modifiers, Qt.KeyboardModifier.NoModifier
        return bool(held & DROP_MODIFIER)

    def import_dialog(self) -> None:
        from PySide6.QtWidgets import QFileDialog  # a dialog's class: imported when one opens

        self.dock.show()
        paths, _ = QFileDialog.getOpenFileNames(
            self.window, "Import sound as haptic", self.window.dialog_folder(),
            f"Sounds ({SOUND_EXTENSIONS})",
        )  # fmt: skip
        if paths:
            track = self.window.import_track()
            self.convert_files([Path(p) for p in paths], track, self.window.arrange.here())

    def convert_files(self, paths: list[Path], track_id: str, at: float) -> None:
        """Analyse sounds in the background; each lands at `at` on the drive track chosen."""
        self.live.stop()  # settings changed just before are this import's: nothing to re-run
        try:
            settings = self.panel.settings()
        except SettingsError as exc:
            self.dock.show()
            self.window.messages.show_message(str(exc), "error")
            return
        for path in paths:
            job = FileJob(
                f"Import of {path.name} as haptic",
                lambda progress, p=path: _analyse(p, settings, progress),
            )
            self.window.run_job(
                job, f"analysing {path.name}…", lambda found: self._analysed(found, track_id, at)
            )

    def _analysed(self, found: ConvertedSound, track_id: str, at: float) -> None:
        doc = self.window.doc
        drive = next((t.id for t in doc.project.tracks if t.id == track_id and t.kind == "drive"),
                     None)  # fmt: skip
        try:
            before = {c.id for t in doc.project.tracks for c in t.clips}
            from timeline.files.convert import place_converted

            project = place_converted(doc.project, found, at=at, drive_track=drive)
            new = [c.id for t in project.tracks for c in t.clips if c.id not in before]
            project = into_gap(project, new, at)
        except HapticTimelineError as exc:
            self.window.messages.show_message(str(exc), "error")
            return
        doc.replace(f"import {found.path.name} as haptic", project)
        self.sounds[found.path.name] = found.path
        self.last_sound = found.path.name
        doc.select_clips(new)
        self.window.view.keep_visible(min(project.find_clip(i)[1].start for i in new))
        a = found.analysis
        self.window.messages.show_message(
            f"{found.path.name} as haptic: {len(a.amplitude)} amplitude and {len(a.frequency)} "
            f"frequency points, {len(a.emphasis)} emphasis; the sound is on an audio track"
            + "".join(f"; {note}" for note in found.notes)
        )

    def live_target(self) -> tuple[str, Path] | None:
        """The converted design the panel re-analyses: the selected one, else the last imported
        (its clip id and sound), or None when there is none left in the project."""
        from timeline.tiles.vibration_tile import VibrationTile

        project = self.window.doc.project
        found: dict[str, str] = {}  # clip id -> sound file name
        for track in project.tracks:
            for clip in track.clips:
                tile = project.tile(clip.tile_id)
                if isinstance(tile, VibrationTile) and tile.source in self.sounds:
                    found[clip.id] = tile.source
        chosen = [c for c in self.window.doc.selected_clips if c in found]
        if not chosen:
            chosen = [c for c, source in found.items() if source == self.last_sound][-1:]
        return (chosen[0], self.sounds[found[chosen[0]]]) if chosen else None

    def reanalyse(self) -> None:
        """Analyse the live target's sound again with the panel's settings (in the background)."""
        target = self.live_target()
        if target is None:
            return
        try:
            settings = self.panel.settings()
        except SettingsError:
            return  # the panel says why
        self._generation += 1
        generation, path = self._generation, target[1]
        job = FileJob(
            f"Re-analysis of {path.name}",
            lambda progress: _reanalyse(path, settings, progress),
        )
        self.window.run_job(job, f"re-analysing {path.name}…",
                            lambda found: self._reanalysed(found, generation))  # fmt: skip

    def _reanalysed(self, found: ConvertedSound, generation: int) -> None:
        if generation != self._generation:
            return  # a later change of settings is being analysed
        target = self.live_target()
        if target is None or target[1] != found.path:
            return
        from timeline.files.convert import reanalysed

        doc = self.window.doc
        try:
            project, new = reanalysed(doc.project, target[0], found.analysis)
        except HapticTimelineError as exc:
            self.window.messages.show_message(str(exc), "error")
            return
        doc.replace(f"re-analyse {found.path.name}", project)
        doc.select_clips([new])
        a = found.analysis
        self.window.messages.show_message(
            f"{found.path.name} re-analysed: {len(a.amplitude)} amplitude and "
            f"{len(a.frequency)} frequency points, {len(a.emphasis)} emphasis"
            + "".join(f"; {note}" for note in found.notes)
        )
