"""The editor window: palette, track headers and lanes, waveform editor, transport, message bar."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

from PySide6.QtCore import QSize, Qt
from PySide6.QtGui import QCloseEvent, QPalette
from PySide6.QtWidgets import (
    QApplication,
    QFrame,
    QGridLayout,
    QMainWindow,
    QScrollArea,
    QSplitter,
    QWidget,
)

from timeline import edits
from timeline.edits.placement import into_gap
from timeline.edits.vibration import with_emphasis
from timeline.errors import HapticTimelineError
from timeline.files import projectfile
from timeline.model import Project

from . import window_state
from .arrange import Arrange
from .clipboard import ClipClipboard
from .document import Document
from .file_jobs import FileJob, export_job, finish_export, import_job
from .first_paint import after_first_paint
from .geometry import LANE_HEIGHT
from .message_bar import MessageBar
from .player import Player
from .ripple import remove_rippled
from .ruler import Ruler
from .scrub import Scrubber
from .sound_import import SoundImport
from .timeline_view import ZOOM_STEP, TimelineView
from .track_header import HeaderColumn
from .transport import Transport

if TYPE_CHECKING:
    from PySide6.QtGui import QAction, QKeySequence
    from PySide6.QtWidgets import QMenu, QMessageBox

    from .autosave import Autosaver, Recoverable
    from .findings_overlay import FindingsOverlay
    from .help import HelpMenu
    from .inspector import Inspector
    from .palette import Palette
    from .waveform_editor import WaveformEditor

APP_NAME = "Haptic Timeline"
DEFAULT_SIZE = (1400, 860)
# splitter: its starting sizes and which panes take a resized window's room
SPLITS = {
    "top": ("top_split", [320, 1080], [0, 1]),
    "bottom": ("bottom_split", [540, 250, 610], [1, 0, 0]),
    "main": ("main_split", [560, 260], [3, 1]),
}
# the smallest the panels built after the first paint may be (their places in the first frame
# are as small, so a small window lays out the same before and after): about their own
# minimum size hints for the palette and the waveform editor, the inspector's scroll area's
PALETTE_MIN, EDITOR_MIN, INSPECTOR_MIN = QSize(256, 160), QSize(345, 181), QSize(120, 68)
# the menu bar's menus, shown by the first frame and filled after it
MENUS = {
    "file": "&File",
    "edit": "&Edit",
    "view": "&View",
    "play": "&Transport",
    "variants": "&Variants",
    "tracks": "T&racks",
    "help": "&Help",
}


def fresh_project(axis: str = "time") -> Project:
    """A new project with the Templates tab filled (once) and one track to start on."""
    project = edits.new_project(axis)
    project, _ = edits.add_track(project, "drive" if axis == "time" else "torque")
    return project


def _screen_rows() -> int:
    """How many lanes the primary screen's height can show at most."""
    screen = QApplication.primaryScreen()
    return 1 + (screen.availableGeometry().height() if screen else 2160) // LANE_HEIGHT


def _scrolled(widget: QWidget) -> QScrollArea:
    """A pane that scrolls instead of widening the window when its content grows."""
    area = QScrollArea()
    area.setWidget(widget)
    area.setWidgetResizable(True)
    area.setFrameShape(QFrame.Shape.NoFrame)
    area.setHorizontalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAsNeeded)
    area.setMinimumWidth(120)
    return area


def _take_place(splitter: QSplitter, index: int, panel: QWidget) -> None:
    """Put `panel` where the splitter's widget at `index` is, at its size and with its minimum
    size, and delete that one.

    (QSplitter.replaceWidget would leave the panel owned by Python, not by the splitter.)
    """
    sizes = splitter.sizes()
    slot = splitter.widget(index)
    assert slot is not None, "a panel's place is held from the window's start"
    panel.setMinimumSize(slot.minimumSize())
    splitter.insertWidget(index, panel)
    slot.hide()
    slot.setParent(None)  # type: ignore[call-overload]
    slot.deleteLater()
    splitter.setSizes(sizes)


class _Slot(QWidget):
    """The place a panel built after the first paint will take: the window's plain background."""

    def __init__(self, minimum: QSize) -> None:
        super().__init__()
        self.setMinimumSize(minimum)
        self.setAutoFillBackground(True)
        self.setBackgroundRole(QPalette.ColorRole.Window)


class MainWindow(QMainWindow):
    """One window for the whole design loop: shape a tile, place it, play it, feel it, undo.

    The first frame shows the lanes (with their headers and ruler), the transport and the menu
    bar; with `panels_after_paint` (the editor's launch) the palette, the waveform editor, the
    inspector and the menus' actions are built right after it, in the places it kept for them,
    with the findings overlay and the track headers below the screen's height.
    Otherwise, and whenever one of those panels is asked for sooner, they are built at once.
    """

    def __init__(
        self,
        project: Project | None = None,
        path: Path | None = None,
        panels_after_paint: bool = False,
    ) -> None:
        super().__init__()
        self.doc = Document(project or fresh_project(), path)
        self.player = Player(self)
        self.jobs: list[FileJob] = []
        self.ask_unsaved: Callable[[], QMessageBox.StandardButton] = self._ask_unsaved
        self.clip_actions: list[QAction] = []
        self._panels: tuple[Palette, WaveformEditor, Inspector] | None = None
        self._findings: FindingsOverlay | None = None
        self._autosaver: Autosaver | None = None
        self._opened = path if project is not None else None  # the journal starts from it
        self._painted = False
        self._build(panels_after_paint)
        if not panels_after_paint:
            self.build_panels()
            self._start_autosave()
        self.transport.device.currentTextChanged.connect(lambda _: self.findings.schedule())
        self.transport.hand_changed.connect(lambda _: self.findings.hand_changed())
        self.doc.changed.connect(self._changed)
        self.doc.message.connect(self.messages.show_message)
        self.doc.outcome.connect(lambda text: self.messages.show_message(text, hold=True))
        self.doc.modified_changed.connect(lambda _: self._update_title())
        self.doc.selection_changed.connect(self._update_actions)
        self.player.position.connect(self._follow_playhead)
        self.player.finished.connect(self._play_finished)
        self.player.notice.connect(lambda text: self.messages.show_message(text, "error"))
        self.player.warm_up_once_painted(self, lambda: self.doc.project)
        self._update_title()
        self._update_actions()
        self.transport.show_position(0.0, self.doc.project.axis)
        self.resize(*DEFAULT_SIZE)
        self.restored = window_state.restore(self)  # size, splitters, docks and hand
        if panels_after_paint:
            after_first_paint(self.view.viewport(), self._first_painted)

    # --- layout ----------------------------------------------------------------------------

    def _build(self, panels_after_paint: bool) -> None:
        doc = self.doc
        self.view = TimelineView(doc)
        # after the first paint too: the track headers below the screen's height
        self.headers = HeaderColumn(doc, _screen_rows() if panels_after_paint else None)
        self.ruler = Ruler(self.view)
        self.ruler.scrubber = Scrubber(self.player, lambda: self.doc.project)
        self.transport = Transport(self.player)
        self.arrange = Arrange(doc, self.view, self.ruler, lambda: self.player.playing)
        self.clipboard = ClipClipboard(doc, self.arrange.here)
        self.messages = MessageBar()
        self.view.verticalScrollBar().valueChanged.connect(
            self.headers.verticalScrollBar().setValue
        )
        self.view.files_dropped.connect(self.import_files)
        self.view.context_requested.connect(self._fill_clip_menu)
        self.transport.play_button.clicked.connect(lambda _=False: self.play_stop())
        self.transport.hand_changed.connect(self._hand_changed)
        self.ruler.clicked.connect(self._ruler_clicked)
        self.ruler.loop_dragged.connect(lambda: self.transport.loop.setChecked(True))
        self.ruler.scrubbed.connect(self._scrubbed)
        self.messages.cancel_requested.connect(self.cancel_jobs)

        lanes = QWidget()
        grid = QGridLayout(lanes)
        grid.setContentsMargins(0, 0, 0, 0)
        grid.setSpacing(0)
        corner = QWidget()
        corner.setFixedSize(self.headers.width(), self.ruler.height())
        grid.addWidget(corner, 0, 0)
        grid.addWidget(self.ruler, 0, 1)
        grid.addWidget(self.headers, 1, 0)
        grid.addWidget(self.view, 1, 1)

        self.top_split = top = QSplitter(Qt.Orientation.Horizontal)
        top.addWidget(_Slot(PALETTE_MIN))
        top.addWidget(lanes)
        self.bottom_split = bottom = QSplitter(Qt.Orientation.Horizontal)
        bottom.addWidget(_Slot(EDITOR_MIN))
        bottom.addWidget(_Slot(INSPECTOR_MIN))
        bottom.addWidget(self.transport)
        self.main_split = main = QSplitter(Qt.Orientation.Vertical)
        main.addWidget(top)
        main.addWidget(bottom)
        for split, sizes, stretch in SPLITS.values():
            splitter = getattr(self, split)
            splitter.setChildrenCollapsible(False)
            splitter.setSizes(sizes)
            for index, factor in enumerate(stretch):
                splitter.setStretchFactor(index, factor)
        self.setCentralWidget(main)
        self.statusBar().addWidget(self.messages, 1)
        self.statusBar().setSizeGripEnabled(False)
        self.menus = {key: self.menuBar().addMenu(title) for key, title in MENUS.items()}
        self.sound_import = SoundImport(self)  # its dock is restored with the window's state

    def _first_painted(self) -> None:
        self._painted = True
        self._start_autosave()
        self.headers.build_rest()
        self.build_panels()

    @property
    def autosaver(self) -> Autosaver:
        """The document's autosave journal (started now if it was not yet: after the first
        paint when the window was made with `panels_after_paint`)."""
        self._start_autosave()
        assert self._autosaver is not None
        return self._autosaver

    def _start_autosave(self) -> None:
        if self._autosaver is not None:
            return
        from .autosave import Autosaver  # platformdirs and the journal: after the first paint

        self._autosaver = saver = Autosaver(self.doc)
        if self._opened is not None:
            saver.on_disk(self._opened)
        saver.failed.connect(lambda text: self.messages.show_message(text, "error"))
        if self.doc.modified:  # changed before the journal was there: recorded now
            saver.save_now()

    @property
    def findings(self) -> FindingsOverlay:
        """The findings check and its shading (built now if it was not yet: after the first
        paint, with the panels, when the window was made with `panels_after_paint`)."""
        if self._findings is None:
            from .findings_overlay import FindingsOverlay  # not on the way to the first paint

            self._findings = FindingsOverlay(
                self.doc, self.view, self.messages, self.player, painted=self._painted
            )
        return self._findings

    def build_panels(self) -> None:
        """Build the palette, the waveform editor, the inspector and the menus' actions (once),
        each panel in the place the first frame kept for it."""
        if self._panels is not None:
            return
        from .help import HelpMenu
        from .inspector import Inspector
        from .palette import Palette
        from .waveform_editor import WaveformEditor

        palette, editor = Palette(self.doc), WaveformEditor(self.doc)
        self._panels = (palette, editor, Inspector(self.doc))
        palette.range_dropped.connect(self._range_dropped)
        for splitter, index, panel in (
            (self.top_split, 0, palette),
            (self.bottom_split, 0, editor),
            (self.bottom_split, 1, _scrolled(self._panels[2])),
        ):
            _take_place(splitter, index, panel)
        self._menus()
        self.rendered_action = self.findings.rendered.add_action(
            self.view_menu, self.findings.show_rendered
        )
        self.help: HelpMenu = HelpMenu(self, self.menus["help"])
        self._update_actions()

    @property
    def tile_palette(self) -> Palette:
        """The tile palette (built now if it was not yet)."""
        self.build_panels()
        assert self._panels is not None
        return self._panels[0]

    @property
    def editor(self) -> WaveformEditor:
        """The waveform editor (built now if it was not yet)."""
        self.build_panels()
        assert self._panels is not None
        return self._panels[1]

    @property
    def inspector(self) -> Inspector:
        """The inspector (built now if it was not yet)."""
        self.build_panels()
        assert self._panels is not None
        return self._panels[2]

    def splitters(self) -> dict[str, QSplitter]:
        """The window's splitters by name (what window_state remembers)."""
        return {name: getattr(self, attribute) for name, (attribute, _, _) in SPLITS.items()}

    def _action(
        self,
        menu: QMenu,
        text: str,
        slot: Callable[[], object],
        shortcut: str | QKeySequence | QKeySequence.StandardKey = "",
        tip: str = "",
    ) -> QAction:
        from PySide6.QtGui import QAction, QKeySequence  # the menus' actions: after the first paint

        action = QAction(text, self)
        if shortcut:
            action.setShortcut(QKeySequence(shortcut))
        action.setStatusTip(tip)
        action.triggered.connect(lambda _=False: slot())
        menu.addAction(action)
        self.addAction(action)
        return action

    def _menus(self) -> None:
        from PySide6.QtGui import QKeySequence

        from .step_menus import fill_history, fill_variants  # the menus come after the first paint

        file = self.menus["file"]
        self._action(file, "&New", lambda: self.new_project("time"), QKeySequence.StandardKey.New)
        self._action(file, "New &position project", lambda: self.new_project("position"))
        self._action(file, "&Open…", self.open_dialog, QKeySequence.StandardKey.Open)
        self.recent_menu = file.addMenu("Open &recent")
        self.recent_menu.aboutToShow.connect(self._fill_recent)
        self._action(file, "&Save", self.save, QKeySequence.StandardKey.Save)
        self._action(file, "Save &as…", self.save_as_dialog, "Ctrl+Shift+S")
        file.addSeparator()
        self._action(file, "&Import…", self.import_dialog, "Ctrl+Shift+I")
        self.sound_import.add_actions(file)
        self._action(file, "&Export…", self.export_dialog, "Ctrl+E")
        file.addSeparator()
        self._action(file, "&Quit", self.close, QKeySequence.StandardKey.Quit)

        edit = self.menus["edit"]
        edit.aboutToShow.connect(self._name_undo_steps)
        self.undo_action = self._action(edit, "&Undo", self.doc.undo, "Ctrl+Z")
        self.redo_action = self._action(edit, "&Redo", self.doc.redo, "Ctrl+Shift+Z")
        self.history_menu = edit.addMenu("&History")
        self.history_menu.aboutToShow.connect(lambda: fill_history(self.history_menu, self.doc))
        edit.addSeparator()
        cut = self._action(edit, "Cu&t", self.clipboard.cut, QKeySequence.StandardKey.Cut)
        copy = self._action(edit, "&Copy", self.clipboard.copy, QKeySequence.StandardKey.Copy)
        self._action(
            edit, "&Paste at playhead", self.clipboard.paste, QKeySequence.StandardKey.Paste
        )
        edit.addSeparator()
        arrange = self.arrange
        self.split_action = self._action(edit, "Spl&it at playhead", arrange.split_here, "S")
        self.split_action.setShortcuts([QKeySequence("S"), QKeySequence("Ctrl+I")])
        self.clip_actions = [
            cut,
            copy,
            self.split_action,
            self._action(edit, "&Duplicate into free space", arrange.duplicate, "Ctrl+D"),
            self._action(edit, "De&lete", self.delete, QKeySequence.StandardKey.Delete),
            self._action(edit, "Nudge &left one grid step", lambda: arrange.nudge(-1), "Alt+Left"),
            self._action(edit, "Nudge &right one grid step", lambda: arrange.nudge(1), "Alt+Right"),
            self._action(edit, "In&vert about mirror line", self.invert, "Ctrl+Shift+M"),
            self._action(edit, "Re&verse", self.reverse, "Ctrl+R"),
            self._action(edit, "&Merge in place", lambda: self.merge(True), "Ctrl+M"),
            self._action(
                edit, "Merge into a &palette tile", lambda: self.merge(False), "Ctrl+Alt+M"
            ),
        ]
        fades = edit.addMenu("Fade &shape")
        for shape in ("linear", "equal-power", "exponential", "s-curve"):
            self._action(fades, shape, lambda s=shape: self.set_fade_shape(s))
        self._action(edit, "Select &all", self.select_all, QKeySequence.StandardKey.SelectAll)
        self.ripple_action = self._action(edit, "Ri&pple edit", self.toggle_ripple)
        self.ripple_action.setCheckable(True)

        view = self.menus["view"]
        self._action(view, "Zoom &in", lambda: self.view.zoom(ZOOM_STEP), "Ctrl+=")
        self._action(view, "Zoom &out", lambda: self.view.zoom(1 / ZOOM_STEP), "Ctrl+-")
        self._action(view, "&Fit project", self.view.fit, "Ctrl+0")
        self.snap_action = self._action(view, "&Snap to edges and grid", self.toggle_snap, "G")
        self.snap_action.setCheckable(True)
        self.snap_action.setChecked(True)
        self.view_menu = view

        play = self.menus["play"]
        self._action(play, "&Play / stop", self.play_stop, "Space")
        self._action(play, "&Loop (the loop region if one is set)", self.transport.loop.toggle, "L")
        play.addSeparator()
        self._action(play, "Add &marker at playhead", arrange.add_marker, "M")
        self._action(play, "&Next marker", lambda: arrange.jump(1), "]")
        self._action(play, "P&revious marker", lambda: arrange.jump(-1), "[")

        var = self.menus["variants"]
        self._action(var, "&Save design as variant", self.save_variant, "Ctrl+Shift+V")
        self._action(var, "Switch to &next variant", self.next_variant, "V")
        self._action(var, "&Delete the active variant", self.delete_variant)
        self._action(var, "&Map of variants by feel…", lambda: self._similarity("variants"))
        self._action(var, "Palette &tab by feel…", lambda: self._similarity("tab"))
        var.addSeparator()
        self.variants_menu = var
        var.aboutToShow.connect(lambda: fill_variants(var, self.doc, self.switch_variant))

        self._action(self.menus["tracks"], "&Add track…", self.headers._show_kinds)

    def _similarity(self, what: str) -> None:
        """Open a map by feel (its module, with the similarity measures, loads on first use)."""
        from .similarity_map import similarity_window

        similarity_window(self, what)

    # --- window state ----------------------------------------------------------------------

    def _changed(self, project: Project) -> None:
        self.player.follow(project)
        self._update_actions()

    def _update_title(self) -> None:
        name = self.doc.path.name if self.doc.path else "untitled"
        star = "*" if self.doc.modified else ""
        self.setWindowTitle(f"{star}{name} — {APP_NAME}")

    def _update_actions(self) -> None:
        has = bool(self.doc.selected_clips)
        for action in self.clip_actions:
            action.setEnabled(has or action is self.split_action)

    def _name_undo_steps(self) -> None:
        """Undo and Redo say which step they take (named when the Edit menu opens, so a drag
        does not work out a name on every mouse move)."""
        history = self.doc.history
        undo, redo = (n.replace("&", "&&") for n in (history.undo_name, history.redo_name))
        self.undo_action.setText(f"&Undo {undo}".rstrip())
        self.redo_action.setText(f"&Redo {redo}".rstrip())

    def _fill_clip_menu(self, menu: QMenu) -> None:
        if not self.doc.selected_clips:
            return
        at = self.view.menu_at
        item = self.view.item_at(self.view.mapFromScene(at).toPointF())
        if item is not None:
            from .gestures.pivot import PivotGesture  # with the first clip menu

            clip_id = item.clip.id
            here = menu.addAction("Set &mirror line here")
            here.setToolTip("The clip's horizontal mirror line at this level (Ctrl+Shift+click)")
            here.triggered.connect(lambda _=False: PivotGesture(self.view, at, clip_id))
            menu.addSeparator()
        for action in self.clip_actions:
            menu.addAction(action)

    def _fill_recent(self) -> None:
        from .recent import recent_files

        self.recent_menu.clear()
        for path in recent_files():
            self.recent_menu.addAction(str(path)).triggered.connect(
                lambda _=False, p=path: self.open_path(p)
            )
        if self.recent_menu.isEmpty():
            self.recent_menu.addAction("(no recent projects)").setEnabled(False)

    # --- clip commands (each one undo step) ------------------------------------------------

    def _each(self, label: str, edit) -> None:
        ids = list(self.doc.selected_clips)
        if not ids:
            self.messages.show_message("select a clip first", "error")
            return

        def all_of(project: Project) -> Project:
            for clip_id in ids:
                project = edit(project, clip_id)
            return project

        self.doc.apply(label, all_of)

    def delete(self) -> None:
        """Remove the selected clips (a design with its emphasis), when the timeline (not another
        region) has focus."""
        focus = QApplication.focusWidget()
        elsewhere = (self.tile_palette, self.editor, self.inspector, self.transport, self.headers)
        if focus is not None and any(r is focus or r.isAncestorOf(focus) for r in elsewhere):
            self.messages.show_message(
                "Delete removes clips when the timeline has focus: click a clip first", "error"
            )
            return
        ids = with_emphasis(self.doc.project, self.doc.selected_clips)
        if ids:
            remove = remove_rippled if self.view.ripple else edits.remove_clips
            self.doc.apply("delete", remove, ids)

    def invert(self) -> None:
        """Mirror the selected clips about their mirror lines."""
        self._each("invert", edits.invert_clip)

    def reverse(self) -> None:
        """Play the selected clips backwards."""
        self._each("reverse", edits.reverse_clip)

    def set_fade_shape(self, shape: str) -> None:
        """Give the selected clips' fades a shape."""

        def shaped(project: Project, clip_id: str) -> Project:
            _, clip = project.find_clip(clip_id)
            project = edits.set_fade(project, clip_id, "in", clip.fade_in.length, shape)
            return edits.set_fade(project, clip_id, "out", clip.fade_out.length, shape)

        self._each(f"{shape} fades", shaped)

    def merge(self, in_place: bool = True) -> None:
        """Superimpose the selected clips into one new tile in the Scratch tab; in place, one
        clip of it replaces them (the design renders the same)."""
        ids = list(self.doc.selected_clips)
        label = "merge in place" if in_place else "merge to palette"
        tile_id = self.doc.apply(label, edits.merge_clips, ids, replace_clips=in_place)
        if tile_id:
            self.doc.select_tile(tile_id)
            where = "; one clip of it replaces them" if in_place else ""
            self.messages.show_message(
                f"merged {len(ids)} clips into a new tile in Scratch{where} (Ctrl+Z undoes)"
            )

    def select_all(self) -> None:
        self.doc.select_clips([c.id for t in self.doc.project.tracks for c in t.clips])

    def toggle_ripple(self) -> None:
        """Ripple edit on or off: trimming an end or deleting moves the later clips along."""
        self.view.ripple = not self.view.ripple
        self.ripple_action.setChecked(self.view.ripple)
        self.messages.show_message("ripple edit on" if self.view.ripple else "ripple edit off")

    def toggle_snap(self) -> None:
        self.view.snapping = not self.view.snapping
        self.snap_action.setChecked(self.view.snapping)
        self.messages.show_message("snapping on" if self.view.snapping else "snapping off")

    def save_variant(self) -> None:
        """Save the design as the next variant (A, B, ...)."""
        from . import variants  # loaded when first used, not on the way to the first paint

        name = variants.next_name(self.doc.project)
        if self.doc.apply("save variant", variants.save_next, name):
            self.messages.show_message(f"saved variant {name}; press V to switch between variants")

    def next_variant(self) -> None:
        """Switch to the next variant, to compare by feel."""
        from . import variants

        if self.doc.apply("switch variant", variants.switch_next):
            self.messages.show_message(f"now playing variant {self.doc.project.active_variant}")

    def switch_variant(self, name: str) -> None:
        """Switch to a named variant (from the Variants menu)."""
        if self.doc.apply("switch variant", edits.switch_variant, name):
            self.messages.show_message(f"now playing variant {name}")

    def delete_variant(self) -> None:
        """Delete the active variant (the only step that removes one; Ctrl+Z brings it back)."""
        name = self.doc.project.active_variant
        if not name:
            self.messages.show_message("no variant is active: switch to the one to delete", "error")
            return
        if self.doc.apply(f"delete variant {name}", edits.remove_variant, name):
            self.messages.show_message(f"deleted variant {name} (Ctrl+Z brings it back)")

    def _range_dropped(self, tab: str, mime) -> None:
        from .waveform_editor import read_range

        tile_id, a, b = read_range(mime)
        self.editor.range_to_palette(tab, tile_id, a, b)

    # --- transport -------------------------------------------------------------------------

    def play_stop(self, start: float | None = None) -> None:
        """Play the project (or the selected clips' tracks) from the cursor (or `start`; the
        loop region when looping over one), or stop."""
        if self.player.playing:
            self.player.stop()
            self.transport.show_playing(False)
            return
        project = self.doc.project
        tracks = None
        if self.transport.selected_only.isChecked():
            tracks = list(
                dict.fromkeys(project.find_clip(c)[0].id for c in self.doc.selected_clips)
            )
            if not tracks:
                self.messages.show_message("select clips on the tracks to play", "error")
                return
        loop = self.transport.loop.isChecked()
        if start is None:
            start = self.view.scene().cursor_u
        start = start if start < project.duration else 0.0
        stop = None
        if loop and project.loop is not None:
            start, stop = project.loop.start, project.loop.stop
        self.transport.scope.clear()
        self.player.play(project, start, stop, loop, tracks)
        self.transport.show_playing(self.player.playing)

    def _hand_changed(self, _hand) -> None:
        """A new hand applies at once: playing restarts where the knob (or the stream) is."""
        if not self.player.playing:
            return
        project = self.doc.project
        if project.axis == "position":
            self.player.play(project, origin=self.player.angle)
        else:
            at = self.player.stream.state.position if self.player.stream else None
            self.player.stop()
            self.play_stop(at)
        self.transport.show_playing(self.player.playing)

    def _scrubbed(self, u: float) -> None:
        """A scrub let go while playing goes on from there: a time project plays on from that
        time, a position project's knob starts again at that angle (felt under the hand)."""
        scrubber = self.ruler.scrubber
        if scrubber is None or not scrubber.was_playing:
            return
        project = self.doc.project
        if project.axis == "position":
            self.player.play(project, origin=u)
            self.transport.show_playing(self.player.playing)
        else:
            self.player.stop()
            self.play_stop(u)

    def _ruler_clicked(self, u: float) -> None:
        self.transport.show_position(u, self.doc.project.axis)

    def _follow_playhead(self, u: float) -> None:
        if self.ruler.scrubber is not None and self.ruler.scrubber.active:
            return  # the playhead is under the mouse while it scrubs
        self.view.scene().set_playhead(u)
        self.view.keep_visible(u)
        self.ruler.update()
        self.transport.show_position(u, self.doc.project.axis)

    def _play_finished(self, error: str) -> None:
        self.transport.show_playing(False)
        if error:
            self.messages.show_message(error, "error")

    # --- files -----------------------------------------------------------------------------

    def new_project(self, axis: str) -> None:
        if self.confirm_discard():
            self._load(fresh_project(axis), None)

    def _load(self, project: Project, path: Path | None) -> None:
        self.player.stop()
        self.autosaver.discard()
        self.doc.reset(project, path)
        self.player.project_replaced(self.doc.project)  # crosses to the play process meanwhile
        self.view.scene().set_playhead(0.0)  # the old playhead means nothing in another project
        self.view.scene().set_cursor(0.0)
        self.transport.scope.clear()
        self.view.fit()
        self.transport.show_position(0.0, project.axis)

    def open_path(self, path: Path) -> bool:
        """Open a project file (after asking about unsaved changes)."""
        from .recent import remember  # File > Open recent's list: not on the way to the first paint

        if not self.confirm_discard():
            return False
        try:
            project = projectfile.load(path)
        except HapticTimelineError as exc:
            self.messages.show_message(str(exc), "error")
            return False
        self._load(project, Path(path))
        self.autosaver.on_disk(Path(path))
        remember(Path(path))
        self.messages.show_message(f"opened {Path(path).name}")
        return True

    def dialog_folder(self) -> str:
        """Where file dialogs open: the project's folder, once it has one."""
        return str(self.doc.path.parent) if self.doc.path else ""

    def open_dialog(self) -> None:
        from PySide6.QtWidgets import QFileDialog  # a dialog's class: imported when one opens

        path, _ = QFileDialog.getOpenFileName(
            self, "Open project", self.dialog_folder(), "Haptic timeline (*.htl)"
        )
        if path:
            self.open_path(Path(path))

    def save_to(self, path: Path) -> bool:
        """Save atomically; the title loses its unsaved mark."""
        from .recent import remember

        try:
            projectfile.save(self.doc.project, path)
        except (HapticTimelineError, OSError) as exc:
            self.messages.show_message(f"could not save: {exc}", "error")
            return False
        self.doc.mark_saved(Path(path))
        self.autosaver.on_disk(Path(path))
        remember(Path(path))
        self.messages.show_message(f"saved {Path(path).name}")
        return True

    def save(self) -> bool:
        if self.doc.path is None:
            return self.save_as_dialog()
        return self.save_to(self.doc.path)

    def save_as_dialog(self) -> bool:
        from PySide6.QtWidgets import QFileDialog

        start = str(self.doc.path) if self.doc.path else ""
        path, _ = QFileDialog.getSaveFileName(
            self, "Save project", start, "Haptic timeline (*.htl)"
        )
        if not path:
            return False
        path = Path(path if path.endswith(".htl") else path + ".htl")
        return self.save_to(path)

    def _extensions(self, key: str) -> str:
        from timeline.plugins.file_formats import all_formats

        found = sorted({e for f in all_formats().values() if getattr(f, key) for e in f.extensions})
        return " ".join(f"*{e}" for e in found)

    def import_dialog(self) -> None:
        from PySide6.QtWidgets import QFileDialog

        paths, _ = QFileDialog.getOpenFileNames(
            self, "Import", self.dialog_folder(), f"Importable ({self._extensions('reads')})"
        )
        if paths:
            self.import_files([Path(p) for p in paths], self.import_track(), self.arrange.here())

    def import_track(self) -> str:
        """Where an import goes: the selected clip's track, else the lane under the pointer,
        else the first track."""
        project = self.doc.project
        if self.doc.selected_clips:
            return project.find_clip(self.doc.selected_clips[0])[0].id
        from PySide6.QtGui import QCursor

        pointer = self.view.viewport().mapFromGlobal(QCursor.pos())
        if self.view.viewport().rect().contains(pointer):
            track = self.view.track_at(self.view.mapToScene(pointer).y())
            if track is not None:
                return track.id
        return project.tracks[0].id if project.tracks else ""

    def import_files(self, paths: list[Path], track_id: str, at: float) -> None:
        """Import files in the background onto a track (its kind gives them meaning).

        Sounds dropped with Alt held are analysed into haptic designs instead.
        """
        if self.sound_import.wants_drop():
            self.sound_import.convert_files(paths, track_id, at)
            return
        for path in paths:
            self.run_job(
                import_job(path),
                f"importing {path.name}…",
                lambda imported, p=path: self._imported(p, imported, track_id, at),
            )

    def _imported(self, path: Path, imported, track_id: str, at: float) -> None:
        project = self.doc.project
        chosen = track_id if any(t.id == track_id for t in project.tracks) else None
        from timeline.files import importing  # with the first import, not at start-up

        try:
            project, clip_ids = importing.place_checked(
                project, imported, path.name, at=at, track_id=chosen
            )
            project = into_gap(project, clip_ids, at)
        except HapticTimelineError as exc:
            self.messages.show_message(str(exc), "error")
            return
        self.doc.replace(f"import {path.name}", project)
        self.doc.select_clips(clip_ids)
        if clip_ids:
            self.view.keep_visible(min(project.find_clip(i)[1].start for i in clip_ids))
        notes = "; ".join(imported.notes)
        self.messages.show_message(f"imported {path.name}" + (f" ({notes})" if notes else ""))

    def export_dialog(self) -> None:
        from PySide6.QtWidgets import QFileDialog

        path, _ = QFileDialog.getSaveFileName(
            self, "Export", self.dialog_folder(), f"Exportable ({self._extensions('writes')})"
        )
        if not path:
            return
        from PySide6.QtWidgets import QDialog

        from .export_options import ExportOptions  # not on the way to the first paint

        dialog = ExportOptions(self.doc.project, Path(path), self)
        if dialog.exec() == QDialog.DialogCode.Accepted:
            self.export_to(Path(path), **dialog.options())

    def export_to(self, path: Path, **options: Any) -> FileJob:
        """Export in the background (with export_project's options: `rate`, `fixed_point`); the
        file appears only when the export has finished."""
        job = export_job(self.doc.project, path, **options)
        self.run_job(job, f"exporting {path.name}…", lambda tmp: self._exported(tmp, path))
        return job

    def _exported(self, tmp: Path, path: Path) -> None:
        try:
            finish_export(tmp, path)
        except OSError as exc:
            tmp.unlink(missing_ok=True)
            self.messages.show_message(f"could not export: {exc.strerror or exc}", "error")
            return
        self.messages.show_message(f"exported {path.name}")

    def run_job(self, job: FileJob, text: str, on_done: Callable[[Any], None]) -> None:
        """Start a file job, listed in `jobs` (with progress and Cancel) until it ends: done
        hands the result to `on_done`, failed and cancelled say so in the message bar."""
        self.jobs.append(job)
        job.progress.connect(self.messages.set_progress)
        job.done.connect(lambda result, j=job: (self._job_ended(j), on_done(result)))
        job.failed.connect(
            lambda error, j=job: (self._job_ended(j), self.messages.show_message(error, "error"))
        )
        job.cancelled.connect(
            lambda j=job: (
                self._job_ended(j),
                self.messages.show_message(f"{j.what} cancelled", hold=True),
            )
        )
        self.messages.show_message(text)
        self.messages.set_progress(0.0)
        job.start()

    def _job_ended(self, job: FileJob) -> None:
        if job in self.jobs:
            self.jobs.remove(job)
        if not self.jobs:
            self.messages.set_progress(None)

    def cancel_jobs(self) -> None:
        """Cancel running imports and exports."""
        for job in self.jobs:
            job.cancel()

    # --- recovery and closing --------------------------------------------------------------

    def offer_recovery(self) -> list[Recoverable]:
        """If a crashed session left an autosave, offer it in the message bar."""
        from .autosave import recoverable

        found = recoverable()
        self.autosaver.offered = found[:1]  # removed at a clean close if not recovered
        if found:
            entry = found[0]
            where = entry.original.name if entry.original else "an untitled project"
            self.messages.offer(
                f"Unsaved work on {where} was recovered from a crash.",
                "Recover",
                lambda: self.recover(entry),
            )
        return found

    def recover(self, entry: Recoverable) -> None:
        """Load an autosave as unsaved changes to its original file."""
        try:
            project = entry.load()
        except HapticTimelineError as exc:
            self.messages.show_message(str(exc), "error")
            return
        self._load(self.doc.project, entry.original)
        self.doc.replace("recover", project)
        self.player.project_replaced(self.doc.project)  # crosses now, as an opened project does
        entry.discard()
        self.messages.show_message("recovered; save to keep it")

    def _ask_unsaved(self) -> QMessageBox.StandardButton:
        from PySide6.QtWidgets import QMessageBox

        buttons = QMessageBox.StandardButton
        return QMessageBox.question(
            self,
            APP_NAME,
            "Save changes before closing?",
            buttons.Save | buttons.Discard | buttons.Cancel,
            buttons.Save,
        )

    def confirm_discard(self) -> bool:
        """With unsaved changes, ask once: save, discard or cancel."""
        if not self.doc.modified:
            return True
        from PySide6.QtWidgets import QMessageBox

        answer = self.ask_unsaved()
        if answer == QMessageBox.StandardButton.Save:
            return self.save()
        return answer == QMessageBox.StandardButton.Discard

    def closeEvent(self, event: QCloseEvent) -> None:
        if not self.confirm_discard():
            event.ignore()
            return
        window_state.save(self)
        self.player.close()
        if self._findings is not None:
            self._findings.close()
        if self._autosaver is not None:
            self._autosaver.close()
        event.accept()
