"""Make the screenshots of docs/tutorial.md by driving the real editor offscreen.

    QT_QPA_PLATFORM=offscreen python docs/img/make_tutorial_screenshots.py

Every step goes through the window as a person's would: menu actions and shortcuts, drops of
palette tiles on a lane, drags on the lanes, values typed into the inspector and the track header,
clicks on the ruler. At the end it prints how the editor's designs compare with the shipped fan
knob's tables (which the tutorial's Python reproduces) and with the buzz's expected sample at
0.25 s. A doc tool, not a test: it writes docs/img/tutorial-*.png.
"""

from __future__ import annotations

import io
import math
import os
import sys
import tempfile
from pathlib import Path

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
_HOME = tempfile.mkdtemp(prefix="tutorial-shots-")
os.environ["XDG_DATA_HOME"] = os.path.join(_HOME, "data")  # autosaves stay out of the user's
os.environ["XDG_CONFIG_HOME"] = os.path.join(_HOME, "config")

from PIL import Image  # noqa: E402
from PySide6.QtCore import (  # noqa: E402
    QBuffer,
    QEvent,
    QIODevice,
    QPoint,
    QPointF,
    QRect,
    QSettings,
    Qt,
)
from PySide6.QtGui import QDragEnterEvent, QDragMoveEvent, QDropEvent  # noqa: E402
from PySide6.QtTest import QTest  # noqa: E402
from PySide6.QtWidgets import QApplication  # noqa: E402

from timeline.gui.gestures.palette_drop import tile_mime  # noqa: E402
from timeline.gui.main_window import MainWindow  # noqa: E402

HERE = Path(__file__).resolve().parent
SIZE = (1280, 800)
NO = Qt.KeyboardModifier.NoModifier
SHIFT = Qt.KeyboardModifier.ShiftModifier
CTRL = Qt.KeyboardModifier.ControlModifier
LEFT = Qt.MouseButton.LeftButton


# --- what a person does ---------------------------------------------------------------------


def settle(ms: int = 50) -> None:
    """Let the window repaint and its timers run."""
    QTest.qWait(ms)


def menu_action(win: MainWindow, menu: str, text: str) -> None:
    """Choose a menu item by its text (ampersands ignored), as a click on it does."""
    for top in win.menuBar().actions():
        if top.text().replace("&", "") == menu:
            for action in top.menu().actions():
                if action.text().replace("&", "").startswith(text):
                    action.trigger()
                    settle()
                    return
    raise LookupError(f"no menu item {menu} → {text}")


def press(win: MainWindow, key: Qt.Key, modifiers=NO) -> None:
    """A key press on the window (its shortcuts)."""
    QTest.keyClick(win, key, modifiers)
    settle()


def add_track(win: MainWindow, label: str) -> str:
    """Tracks → Add track…, then the kind's entry of the menu that opens."""
    menu = win.headers.kind_menu()
    for action in menu.actions():
        if action.text().startswith(label):
            action.trigger()
            settle()
            return win.doc.project.tracks[-1].id
    raise LookupError(f"no track kind {label}")


def template(win: MainWindow, name: str) -> str:
    """The id of a Templates tile by its name."""
    project = win.doc.project
    for tile_id in project.tab("Templates").tile_ids:
        if project.tile(tile_id).name == name:
            return tile_id
    raise LookupError(f"no template {name}")


def lane_point(win: MainWindow, track_id: str, u: float) -> QPoint:
    """The viewport pixel at axis position u, halfway down a track's lane."""
    g = win.view.geometry
    y = g.lane_top(win.view.lane_of(track_id)) + g.lane_height / 2
    return win.view.mapFromScene(QPointF(g.x(u), y))


def drop_tile(win: MainWindow, tile_id: str, track_id: str, u: float) -> str:
    """Drag a palette tile and release it on a lane: what Qt delivers to the lanes."""
    at = lane_point(win, track_id, u)
    vp = win.view.viewport()
    mime, copy, none = tile_mime(tile_id), Qt.DropAction.CopyAction, Qt.MouseButton.NoButton
    before = {c.id for t in win.doc.project.tracks for c in t.clips}
    QApplication.sendEvent(vp, QDragEnterEvent(at, copy, mime, none, NO))
    QApplication.sendEvent(vp, QDragMoveEvent(at, copy, mime, none, NO))
    QApplication.sendEvent(vp, QDropEvent(QPointF(at), copy, mime, none, NO, QEvent.Type.Drop))
    settle()
    (new,) = {c.id for t in win.doc.project.tracks for c in t.clips} - before
    return new


def clip_point(win: MainWindow, clip_id: str, fx: float = 0.5, fy: float = 0.6) -> QPoint:
    rect = win.view.clip_scene_rect(clip_id)
    scene = QPointF(rect.left() + fx * rect.width(), rect.top() + fy * rect.height())
    return win.view.mapFromScene(scene)


def click_clip(win: MainWindow, clip_id: str) -> None:
    QTest.mouseClick(win.view.viewport(), LEFT, NO, clip_point(win, clip_id))
    settle()


def drag(win: MainWindow, start: QPoint, end: QPoint, modifiers=NO, steps: int = 8) -> None:
    vp = win.view.viewport()
    QTest.mousePress(vp, LEFT, modifiers, start)
    for i in range(1, steps + 1):
        QTest.mouseMove(vp, start + (end - start) * (i / steps))
    QTest.mouseRelease(vp, LEFT, modifiers, end)
    settle()


def type_into(box, value: float) -> None:
    """Click a number box, select its text, type a value and press Enter."""
    box.setFocus()
    box.selectAll()
    text = f"{value:g}"
    QTest.keyClicks(box, text)
    QTest.keyClick(box, Qt.Key.Key_Return)
    settle()


def inspect(win: MainWindow, **values: float) -> None:
    """Type the selected tile's parameters into the inspector (shown units: s, °, Hz, ...)."""
    for name, value in values.items():
        type_into(win.inspector.boxes[name], value)


def click_ruler(win: MainWindow, u: float) -> None:
    QTest.mouseClick(win.ruler, LEFT, NO, QPoint(int(round(win.ruler.x_of(u))), 20))
    settle()


def lanes(win: MainWindow, count: int) -> QRect:
    """The ruler, track headers and the first `count` lanes (window coordinates)."""
    top_left = win.ruler.mapTo(win, QPoint(0, 0))
    left = win.headers.mapTo(win, QPoint(0, 0)).x()
    view = win.view.mapTo(win, QPoint(0, 0))
    bottom = view.y() + count * win.view.geometry.lane_height + 30
    return QRect(QPoint(left, top_left.y()), QPoint(view.x() + win.view.width(), bottom))


def shot(win: MainWindow, name: str, *regions) -> Path:
    """Save the window, or the smallest rectangle holding some of its widgets, as
    docs/img/<name>.png in at most 256 colours (a flat UI keeps its look, undithered)."""
    settle(150)
    pixmap = win.grab()
    if regions:
        box = QRect()
        for region in regions:
            if not isinstance(region, QRect):
                region = QRect(region.mapTo(win, QPoint(0, 0)), region.size())
            box = box.united(region)
        pixmap = pixmap.copy(box.adjusted(-2, -2, 2, 2).intersected(pixmap.rect()))
    data = QBuffer()
    data.open(QIODevice.OpenModeFlag.WriteOnly)
    pixmap.save(data, "PNG")
    image = Image.open(io.BytesIO(bytes(data.data()))).convert("RGB")
    path = HERE / f"{name}.png"
    image.quantize(256, Image.Quantize.MEDIANCUT, dither=Image.Dither.NONE).save(
        path, optimize=True
    )
    print(f"wrote {path.name}: {image.width}x{image.height}, {path.stat().st_size // 1024} KB")
    return path


# --- the phone buzz (time axis) -------------------------------------------------------------


def buzz(win: MainWindow, folder: Path) -> Path:
    """Part 2 of the tutorial: a 175 Hz buzz with a fade-out, then an emphasis as variant B."""
    menu_action(win, "File", "New")  # a time project with one drive track, Drive 1
    win.transport.hand.setCurrentText("hold")  # the hand holds the knob still (the default)
    drive = win.doc.project.tracks[0].id
    sine = drop_tile(win, template(win, "sine"), drive, 0.0)
    click_clip(win, sine)
    inspect(win, frequency=175, length=0.5)  # the first edit copies the template into Scratch
    type_into(win.headers.headers[drive].gain, 0.5)  # the track header's gain box
    press(win, Qt.Key.Key_0, CTRL)  # View → Fit project
    shot(win, "tutorial-buzz-1-sine", win.headers, win.view, win.inspector)
    rect = win.view.clip_scene_rect(sine)
    handle = win.view.mapFromScene(QPointF(rect.right() - 1, rect.top() + 3))
    drag(win, handle, handle - QPoint(round(0.1 * win.view.geometry.px_per_unit), 0))
    fade_menu = next(a.menu() for a in win.menuBar().actions()[1].menu().actions()
                     if a.menu() and a.text().replace("&", "") == "Fade shape")  # fmt: skip
    # Edit → Fade shape → exponential
    next(a for a in fade_menu.actions() if a.text() == "exponential").trigger()
    settle()
    shot(win, "tutorial-buzz-2-fade", lanes(win, 1))
    press(win, Qt.Key.Key_V, CTRL | SHIFT)  # Variants → Save design as variant: A
    kick = drop_tile(win, template(win, "emphasis"), drive, 0.0)
    click_clip(win, kick)
    inspect(win, frequency=0.633, amplitude=0.8)  # 0.633 of 80..230 Hz: 175 Hz
    press(win, Qt.Key.Key_V, CTRL | SHIFT)  # variant B: with the emphasis
    for _ in range(5):
        press(win, Qt.Key.Key_Equal, CTRL)  # View → Zoom in: the two clips overlap at the start
    win.view.horizontalScrollBar().setValue(0)
    shot(win, "tutorial-buzz-3-emphasis", lanes(win, 1))
    path = folder / "buzz.htl"
    win.save_to(path)  # File → Save as… buzz.htl
    return path


# --- the fan knob (position axis) -----------------------------------------------------------


def fan_knob(win: MainWindow, folder: Path) -> Path:
    """Part 1 of the tutorial: walls, four detents, damping and mass over angle."""
    deg = math.radians
    menu_action(win, "File", "New position project")  # one torque track, Torque 1
    torque = win.doc.project.tracks[0].id
    damping = add_track(win, "Damping")  # Tracks → Add track… → Damping
    mass = add_track(win, "Mass")
    detents = drop_tile(win, template(win, "detents"), torque, deg(20))
    click_clip(win, detents)
    inspect(win, length=240, count=4, amplitude=0.25, phase=-0.5)
    type_into(win.headers.headers[torque].gain, 0.8)
    press(win, Qt.Key.Key_0, CTRL)
    shot(win, "tutorial-fan-1-detents", win.headers, win.view, win.inspector)
    high = drop_tile(win, template(win, "wall"), torque, deg(260))
    click_clip(win, high)
    inspect(win, length=20)
    press(win, Qt.Key.Key_C, CTRL)  # copy the wall,
    click_ruler(win, 0.0)  # put the playhead at 0°
    press(win, Qt.Key.Key_V, CTRL)  # and paste it there, on the same track
    low = next(c for c in win.doc.selected_clips if c != high)
    press(win, Qt.Key.Key_R, CTRL)  # Edit → Reverse
    press(win, Qt.Key.Key_M, CTRL | SHIFT)  # Edit → Invert about mirror line
    for start, length, value in ((0, 20, 0.3), (20, 240, 0.2)):
        level = drop_tile(win, template(win, "constant"), damping, deg(start))
        click_clip(win, level)
        inspect(win, length=length, value=value)
        if start == 0:
            press(win, Qt.Key.Key_C, CTRL)
            click_ruler(win, deg(260))
            press(win, Qt.Key.Key_V, CTRL)
    whole = drop_tile(win, template(win, "constant"), mass, 0.0)
    click_clip(win, whole)
    inspect(win, length=280, value=0.2)
    for name, at in (("Off", 50), ("Lo", 110), ("Med", 170), ("Hi", 230)):
        click_ruler(win, deg(at))
        press(win, Qt.Key.Key_M)  # Transport → Add marker at playhead (M1, M2, ...)
        win.ruler.ask_name = lambda current, n=name: n  # what is typed into the rename box
        QTest.mouseDClick(win.ruler, LEFT, NO, QPoint(round(win.ruler.x_of(deg(at))) + 3, 7))
        settle()
    press(win, Qt.Key.Key_0, CTRL)
    click_clip(win, low)
    shot(win, "tutorial-fan-2-design", win.menuBar(), win.palette, win.view)
    path = folder / "fan.htl"
    win.save_to(path)
    return path


def play_turning(win: MainWindow, speed: float) -> None:
    """Hand: turn at a speed (°/s), then Space; wait until the sweep ends."""
    win.transport.hand.setCurrentText("turn")
    type_into(win.transport.hand_value, speed)
    press(win, Qt.Key.Key_Space)
    for _ in range(400):
        if not win.player.playing:
            break
        settle(50)
    settle(300)


def main() -> None:
    app = QApplication.instance() or QApplication(sys.argv[:1])
    app.setOrganizationName("haptic-timeline-screenshots")
    QSettings.setDefaultFormat(QSettings.Format.IniFormat)
    QSettings.setPath(QSettings.Format.IniFormat, QSettings.Scope.UserScope, _HOME)
    folder = Path(_HOME)
    win = MainWindow()
    win.resize(*SIZE)
    win.show()
    settle(200)
    fan = fan_knob(win, folder)
    play_turning(win, 90.0)
    shot(win, "tutorial-fan-3-played", win.ruler, win.view, win.transport)
    buzz_path = buzz(win, folder)
    win.close()
    app.clipboard().clear()  # the offscreen platform crashes at exit while it holds clips
    report(fan, buzz_path)


def report(fan: Path, buzz_path: Path) -> None:
    """How the editor's designs compare with what the tutorial says they are."""
    from timeline import render
    from timeline.files import projectfile
    from timeline.rendering.playback import position_table, rest_angles

    made, _ = position_table(projectfile.load(fan))
    shipped, _ = position_table(projectfile.load(HERE.parents[1] / "projects" / "fan_knob.htl"))
    worst = max(abs(getattr(made, k) - getattr(shipped, k)).max() for k in ("torque", "damping"))
    rests = ", ".join(f"{math.degrees(a):.2f}" for a in rest_angles(made))
    print(f"fan knob: rest angles {rests} deg; largest difference from projects/fan_knob.htl "
          f"{worst:.3g} (SI)")  # fmt: skip
    phone = projectfile.load(buzz_path)
    drive = render(phone)["drive"]
    fade = phone.tracks[0].clips[0].fade_out
    expected = 0.5 * 0.18 * math.sin(2 * math.pi * 175 * 0.25)
    print(f"buzz: drive at 0.25 s {drive[2500]:.6f} N*m (expected {expected:.6f}), fade-out "
          f"{fade.length:.4f} s {fade.shape}")  # fmt: skip


if __name__ == "__main__":
    main()
