"""Files the way a person handles them: drops from the desktop, New / Open, recent files, palette
tiles saved and loaded, and export progress."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import scipy.io
import soundfile
from PySide6.QtCore import QMimeData, QPoint, QPointF, QSettings, Qt, QUrl
from PySide6.QtTest import QTest
from PySide6.QtWidgets import QFileDialog

from timeline import edits
from timeline.files import exporting, projectfile
from timeline.tiles import SampledTile

from .conftest import two_track_project
from .helpers import drag, send_drop, view_point

CTRL = Qt.KeyboardModifier.ControlModifier
PX = 200.0  # pixels per second in the window fixture


def undo(win) -> None:
    QTest.keyClick(win, Qt.Key.Key_Z, CTRL)


def saved_project(path: Path, gain: float) -> Path:
    """The two-track project with the first clip's gain set, saved to path."""
    project, ids = two_track_project()
    projectfile.save(edits.set_clip_gain(project, ids["c1"], gain), path)
    return path


def choose_file(monkeypatch, method: str, path: Path | str, chosen_filter: str = "") -> None:
    """Make the next QFileDialog.<method> answer as if the user picked path."""
    monkeypatch.setattr(QFileDialog, method, lambda *args, **kwargs: (str(path), chosen_filter))


def test_file_dropped_from_the_desktop_lands_on_that_track_at_the_drop_time(
    window, qtbot, tmp_path
):
    win = window
    samples = np.sin(np.linspace(0, 40, 5000)).astype("float32")
    wav = tmp_path / "buzz.wav"
    soundfile.write(wav, samples, 10_000, subtype="FLOAT")
    before = win.doc.project
    mime = QMimeData()
    mime.setUrls([QUrl.fromLocalFile(str(wav))])
    lane = win.view.lane_geometry.lane_top(1) + 30  # the second drive track
    send_drop(win, mime, view_point(win, QPointF(3.0 * PX, lane)))
    qtbot.waitUntil(lambda: not win.jobs, timeout=10_000)
    clips = win.doc.project.track(win.ids["t2"]).clips
    assert len(clips) == 2
    dropped = clips[-1]
    assert dropped.start == pytest.approx(3.0, abs=1 / PX)
    tile = win.doc.project.tile(dropped.tile_id)
    assert isinstance(tile, SampledTile) and tile.rate == 10_000
    np.testing.assert_allclose(tile.data, samples, atol=1e-7)
    assert win.doc.selected_clips == [dropped.id]
    assert "imported buzz.wav" in win.messages.text
    undo(win)
    assert win.doc.project == before


def test_new_asks_about_unsaved_changes_then_starts_fresh(window):
    win = window
    win.doc.select_clips([win.ids["c1"]])
    win.reverse()
    QTest.keyClick(win, Qt.Key.Key_N, CTRL)
    assert win.asked == 1
    project = win.doc.project
    assert [t.kind for t in project.tracks] == ["drive"]
    assert not [c for t in project.tracks for c in t.clips]
    assert len(project.tab("Templates").tile_ids) >= 14
    assert win.doc.path is None and not win.doc.modified
    assert win.windowTitle().startswith("untitled")


def test_open_reads_the_chosen_file_and_a_cancelled_dialog_changes_nothing(
    window, monkeypatch, tmp_path
):
    win = window
    path = saved_project(tmp_path / "louder.htl", 1.75)
    choose_file(monkeypatch, "getOpenFileName", path, "Haptic timeline (*.htl)")
    QTest.keyClick(win, Qt.Key.Key_O, CTRL)
    assert win.doc.path == path
    assert win.doc.project == projectfile.load(path)
    assert win.doc.project.find_clip(win.ids["c1"])[1].gain == 1.75
    assert win.windowTitle().startswith("louder.htl")
    assert win.messages.text == "opened louder.htl"
    opened = win.doc.project
    choose_file(monkeypatch, "getOpenFileName", "")
    QTest.keyClick(win, Qt.Key.Key_O, CTRL)
    assert win.doc.project is opened and win.doc.path == path


def test_recent_menu_lists_opened_projects_newest_first_and_remembers_them(
    window, monkeypatch, tmp_path, settings_home
):
    win = window
    first = saved_project(tmp_path / "first.htl", 0.5)
    second = saved_project(tmp_path / "second.htl", 0.25)
    for path in (first, second):
        choose_file(monkeypatch, "getOpenFileName", path)
        QTest.keyClick(win, Qt.Key.Key_O, CTRL)
    win.recent_menu.aboutToShow.emit()
    listed = [a.text() for a in win.recent_menu.actions()]
    assert listed == [str(second.resolve()), str(first.resolve())]
    stored = QSettings().value("recent_files", [], type=list)
    assert stored == listed
    ini = list(settings_home.rglob("*.ini"))
    assert len(ini) == 1 and "second.htl" in ini[0].read_text()
    win.recent_menu.actions()[1].trigger()
    assert win.doc.path == first.resolve()
    assert win.doc.project.find_clip(win.ids["c1"])[1].gain == 0.5
    win.recent_menu.aboutToShow.emit()
    assert [a.text() for a in win.recent_menu.actions()] == [
        str(first.resolve()),
        str(second.resolve()),
    ]


def click_tile(win, tab: str, tile_id: str) -> None:
    """Click a tile's thumbnail in a palette tab."""
    win.tile_palette.tabs.setCurrentWidget(win.tile_palette.tile_list(tab))
    tiles = win.tile_palette.tile_list(tab)
    role = Qt.ItemDataRole.UserRole
    item = next(tiles.item(i) for i in range(tiles.count()) if tiles.item(i).data(role) == tile_id)
    at = tiles.visualItemRect(item).center()
    QTest.mouseClick(
        tiles.viewport(), Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, at
    )


def read_column(path: Path) -> np.ndarray:
    """The value column of a saved tile, read back without the editor's readers."""
    if path.suffix == ".mat":
        return scipy.io.loadmat(path)["value"].ravel()
    if path.suffix == ".wav":
        return soundfile.read(path, dtype="float64")[0]
    return np.loadtxt(path, comments="%", delimiter="," if path.suffix == ".csv" else None,
                      skiprows=1 if path.suffix == ".csv" else 0)[:, 1]  # fmt: skip


@pytest.mark.parametrize(
    ("chosen_filter", "suffix"),
    [
        ("MATLAB (*.mat)", ".mat"),
        ("Text, Matlab-readable (*.txt)", ".txt"),
        ("CSV (*.csv)", ".csv"),
        ("WAV (*.wav)", ".wav"),
    ],  # fmt: skip
)
def test_save_tile_as_writes_the_selected_tile(
    window, monkeypatch, tmp_path, chosen_filter, suffix
):
    win = window
    click_tile(win, "Templates", win.ids["ramp"])  # 0.5 s from 0 to 1 at the project's 10 kHz
    assert win.doc.selected_tile == win.ids["ramp"]
    choose_file(monkeypatch, "getSaveFileName", tmp_path / "my ramp", chosen_filter)
    before = win.doc.project
    QTest.mouseClick(win.tile_palette.save_button, Qt.MouseButton.LeftButton)
    path = tmp_path / f"my ramp{suffix}"
    values = read_column(path)
    assert len(values) == 5000
    np.testing.assert_allclose(values, np.arange(5000) / 5000, atol=1e-6)
    assert win.messages.text == f"saved tile ramp to my ramp{suffix}"
    assert win.doc.project is before


def test_load_tile_adds_the_file_to_the_current_tab_as_one_step(window, monkeypatch, tmp_path):
    win = window
    t = np.arange(100) / 1000
    values = np.round(np.sin(2 * np.pi * 30 * t), 6)
    path = tmp_path / "wobble.txt"
    np.savetxt(path, np.column_stack([t, values]), header="time\tvalue", comments="% ")
    win.tile_palette.tabs.setCurrentWidget(win.tile_palette.tile_list("Scratch"))
    before = win.doc.project
    choose_file(monkeypatch, "getOpenFileName", path)
    QTest.mouseClick(win.tile_palette.load_button, Qt.MouseButton.LeftButton)
    added = win.doc.project.tab("Scratch").tile_ids
    assert len(added) == 1
    tile = win.doc.project.tiles[added[0]]
    assert isinstance(tile, SampledTile) and tile.rate == pytest.approx(1000)
    np.testing.assert_allclose(tile.data, values)
    assert win.doc.selected_tile == added[0]
    assert win.tile_palette.tile_list("Scratch").count() == 1
    undo(win)
    assert win.doc.project == before


def files_in(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir() if p.is_file())


def test_export_progress_rises_to_one_and_cancel_leaves_no_file(window, qtbot, tmp_path):
    win = window
    win.doc.apply("add clip", edits.add_clip, win.ids["t3"], win.ids["sine"], 60.0)  # 61 s
    shown: list[int] = []  # what the message bar's progress showed, in thousandths
    win.messages.progress.valueChanged.connect(shown.append)
    target = tmp_path / "long.wav"
    win.export_to(target)
    assert win.messages.progress.isVisible() and win.messages.cancel.isVisible()
    qtbot.waitUntil(lambda: not win.jobs, timeout=20_000)
    assert shown[0] == 0 and shown[-1] == 1000
    assert all(a < b for a, b in zip(shown, shown[1:], strict=False))
    assert len(shown) >= 5  # rendering reports chunk by chunk
    assert not win.messages.progress.isVisible()
    data, rate = soundfile.read(target)
    assert rate == 10_000 and data.shape == (610_000, 2)

    win.messages.progress.valueChanged.connect(lambda value: value and win.cancel_jobs())
    win.export_to(tmp_path / "cancelled.wav")
    qtbot.waitUntil(lambda: not win.jobs, timeout=20_000)
    assert files_in(tmp_path) == ["long.wav"]
    assert "cancelled" in win.messages.text


def test_an_export_stopped_midway_by_its_progress_callback_leaves_nothing(window, tmp_path):
    project = edits.add_clip(window.doc.project, window.ids["t1"], window.ids["sine"], 60.0)[0]
    heard: list[float] = []

    def stop_at_the_third(fraction: float) -> None:
        heard.append(fraction)
        if len(heard) == 3:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        exporting.export_project(project, tmp_path / "half.csv", progress=stop_at_the_third)
    assert 0 < heard[-1] < exporting.RENDER_SHARE
    assert files_in(tmp_path) == []


def test_a_drag_is_announced_once_in_the_message_bar(window):
    win = window
    start = view_point(win, win.view.clip_scene_rect(win.ids["c1"]).center())
    drag(win, start, start + QPoint(100, 0))
    assert win.messages.text == "move clip (Ctrl+Z undoes)"
    assert [m for m, _ in win.messages.history].count("move clip (Ctrl+Z undoes)") == 1
