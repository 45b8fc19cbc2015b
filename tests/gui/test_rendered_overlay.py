"""View > Show rendered by device: the device's output over the lanes, toggled as a person does."""

from __future__ import annotations

import numpy as np
import pytest
from PySide6.QtCore import QSettings, Qt

from tests.gui.helpers import choose
from timeline import edits
from timeline.gui.lane_scale import level_y
from timeline.gui.rendered_overlay import SETTING, RenderedCurve

MAX = 0.18  # N*m: the simulated knob's maximum torque, the drive lanes' full scale


def toggle_from_view_menu(win, qtbot) -> None:
    """Open View on the menu bar with the mouse, then pick the item with the keyboard."""
    bar = win.menuBar()
    view = next(a for a in bar.actions() if a.text() == "&View")
    qtbot.mouseClick(bar, Qt.MouseButton.LeftButton, pos=bar.actionGeometry(view).center())
    menu = view.menu()
    qtbot.waitUntil(menu.isVisible, timeout=5_000)
    rows = [a for a in menu.actions() if not a.isSeparator()]
    target = rows.index(win.rendered_action)
    for _ in range(target + 1):
        qtbot.keyClick(menu, Qt.Key.Key_Down)
    assert menu.activeAction() is win.rendered_action
    qtbot.keyClick(menu, Qt.Key.Key_Return)
    qtbot.waitUntil(lambda: not menu.isVisible(), timeout=5_000)


def curves(win) -> list[RenderedCurve]:
    return [i for i in win.view.scene().items() if isinstance(i, RenderedCurve)]


@pytest.fixture
def loud_window(window, qtbot):
    """The sine on the first drive lane at gain 2: 0.36 N*m designed, twice the knob's maximum."""
    win = window
    win.doc.replace("louder", edits.set_clip_gain(win.doc.project, win.ids["c1"], 2.0))
    qtbot.waitUntil(lambda: win.findings.settled, timeout=20_000)
    return win


def test_off_by_default_and_nothing_drawn(loud_window) -> None:
    win = loud_window
    assert not win.rendered_action.isChecked()
    assert curves(win) == [] and win.findings.traces == ()


def test_the_overlay_shows_the_clamp_where_the_design_exceeds_the_device(loud_window, qtbot):
    win = loud_window
    toggle_from_view_menu(win, qtbot)
    assert win.rendered_action.isChecked() and QSettings().value(SETTING, type=bool)
    qtbot.waitUntil(lambda: win.findings.settled and bool(curves(win)), timeout=30_000)
    (trace,) = win.findings.traces
    assert trace.designed.max() == pytest.approx(2 * MAX, rel=1e-3)  # what was drawn
    assert trace.rendered.max() == pytest.approx(MAX, rel=1e-9)  # what the motor gives
    assert trace.rendered.min() == pytest.approx(-MAX, rel=1e-9)
    lanes = sorted(c.lane for c in curves(win))
    assert lanes == [0, 1]  # both drive lanes, not the stiffness lane
    g = win.view.lane_geometry
    first = next(c for c in curves(win) if c.lane == 0)
    columns, lows, highs = first.columns()
    assert highs.max() == pytest.approx(MAX) and lows.min() == pytest.approx(-MAX)
    box = first.path().boundingRect()
    assert box.top() == pytest.approx(level_y(g, 0, 1.0))  # flat at full scale, not above it
    assert box.bottom() == pytest.approx(level_y(g, 0, -1.0))
    assert box.left() == pytest.approx(0.0) and box.right() == pytest.approx(g.x(2.5), abs=1.0)
    assert len(columns) == pytest.approx(g.x(2.5), abs=2)  # one column per pixel
    assert "Rendered by the device" in first.toolTip()
    win.grab().save("/tmp/rendered_overlay.png")

    # An edit is followed: at gain 0.5 the sine fits and the rendering equals the design.
    win.doc.replace("softer", edits.set_clip_gain(win.doc.project, win.ids["c1"], 0.5))
    qtbot.waitUntil(lambda: win.findings.settled and bool(curves(win)), timeout=30_000)
    (trace,) = win.findings.traces
    sine = (trace.time >= 0.5) & (trace.time < 1.5)  # the ramp on the second lane follows it
    assert trace.rendered[sine].max() == pytest.approx(0.5 * MAX, rel=1e-3)
    np.testing.assert_allclose(trace.rendered, trace.designed, atol=1e-3 * MAX)

    toggle_from_view_menu(win, qtbot)  # off: the curves go, nothing more is rendered
    assert curves(win) == [] and not QSettings().value(SETTING, type=bool)
    win.findings.schedule()
    qtbot.waitUntil(lambda: win.findings.settled, timeout=20_000)
    assert curves(win) == [] and win.findings.traces == ()


def test_the_choice_is_remembered_by_the_next_window(qtbot) -> None:
    from timeline.gui.main_window import MainWindow

    QSettings().setValue(SETTING, True)
    win = MainWindow()
    qtbot.addWidget(win)
    assert win.rendered_action.isChecked() and win.findings.rendered.shown
    win.player.close()
    win.autosaver.discard()


def test_choosing_another_hand_renders_the_knob_again(loud_window, qtbot) -> None:
    win = loud_window
    toggle_from_view_menu(win, qtbot)
    qtbot.waitUntil(lambda: win.findings.settled and bool(curves(win)), timeout=30_000)
    assert win.findings.traces[0].label.endswith("hand hold")
    box = win.transport.hand
    choose(qtbot, box, "free")
    assert win.player.hand.mode == "free"
    qtbot.waitUntil(
        lambda: win.findings.settled and win.findings.traces[0].label.endswith("hand free"),
        timeout=30_000,
    )
    (trace,) = win.findings.traces
    assert trace.rendered.max() == pytest.approx(MAX, rel=1e-9)  # the clamp does not depend on it
    assert all("hand free" in c.toolTip() for c in curves(win))


def test_a_design_too_short_to_render_says_so_once_and_keeps_its_findings(window, qtbot) -> None:
    from timeline import generator

    win = window
    p = edits.new_project()
    p, tile = edits.add_tile(p, generator("constant", 0.0004, "blip", value=1.0))
    p, track = edits.add_track(p, "drive")
    p, _clip = edits.add_clip(p, track, tile, 0.0)  # 4 samples at 10 kHz
    win.doc.replace("blip", p)
    toggle_from_view_menu(win, qtbot)
    qtbot.waitUntil(lambda: win.findings.settled, timeout=20_000)
    said = "Cannot show the rendered output: the design is too short to plot as it renders"
    assert win.messages.text == said and curves(win) == []
    shown = len(win.messages.history)
    win.findings.schedule()
    qtbot.waitUntil(lambda: win.findings.settled, timeout=20_000)
    assert len(win.messages.history) == shown and win.findings.report.findings == ()


def test_an_lra_on_the_knob_is_a_second_curve_showing_what_it_cannot_play(qapp) -> None:
    from dataclasses import replace

    from tests.gui.conftest import two_track_project
    from timeline.gui.geometry import Geometry
    from timeline.gui.rendered_overlay import curves as draw
    from timeline.gui.rendered_overlay import peaks_of
    from timeline.limits.actuators import actuator
    from timeline.limits.plot import traces
    from timeline.plugins.device_protocol import Hand, open_device

    project, _ids = two_track_project()
    with open_device("sim") as sim:
        info = replace(sim.info, actuator=actuator("lra-175"))
    lra, knob = traces(project, info, info.actuator, Hand("hold"), "normal")
    assert lra.designed.max() == pytest.approx(MAX) and knob.rendered.max() == pytest.approx(MAX)
    assert lra.rendered.max() < 0.01 * MAX  # a 5 Hz sine and a 2 Hz ramp, far below 175 Hz
    items = draw(project, [lra, knob], [peaks_of(lra), peaks_of(knob)], Geometry(200.0))
    assert [(c.lane, c.trace.label) for c in items] == [
        (0, "drive on lra-175"), (1, "drive on lra-175"),
        (0, "torque on sim, hand hold"), (1, "torque on sim, hand hold"),
    ]  # fmt: skip
    assert items[0].pen().color() != items[2].pen().color()
    assert items[0].columns()[2].max() < 0.01 * MAX
    assert items[2].columns()[2].max() == pytest.approx(MAX)


@pytest.fixture
def detent_window(qtbot):
    """A position project: a torque sine of 0.3 N*m (above the knob's 0.18) over 0-90 degrees,
    four periods, at 400 px per radian."""
    from timeline import generator
    from timeline.gui.main_window import MainWindow

    p = edits.new_project("position")
    p, track = edits.add_track(p, "torque")
    p = edits.set_track(p, track, full_scale=MAX)
    p, tile = edits.add_tile(p, generator("sine", np.pi / 2, "detents", frequency=8 / np.pi))
    p, _ = edits.add_clip(p, track, tile, 0.0, gain=0.3 / MAX)
    win = MainWindow(p)
    win.ask_unsaved = lambda: None
    qtbot.addWidget(win)
    win.resize(1300, 800)
    win.show()
    qtbot.waitExposed(win)
    win.view.lane_geometry.px_per_unit = 400.0
    win.view.refresh()
    yield win
    win.player.close()
    win.autosaver.discard()


def test_a_position_project_shows_the_torque_against_the_angle_after_the_clamp(
    detent_window, qtbot
) -> None:
    win = detent_window
    toggle_from_view_menu(win, qtbot)
    qtbot.waitUntil(lambda: win.findings.settled and bool(curves(win)), timeout=30_000)
    (trace,) = win.findings.traces
    assert trace.axis == "position" and trace.label.endswith("hand turn:90")  # hold turns here
    assert trace.designed.max() == pytest.approx(0.3, rel=0.02)
    (curve,) = curves(win)
    x, lows, highs = curve.columns()
    drawn = np.isfinite(highs)
    assert np.nanmax(highs) == pytest.approx(MAX, rel=1e-9)  # flat at the clamp, not 0.3
    assert np.nanmin(lows) == pytest.approx(-MAX, rel=1e-9)
    g = win.view.lane_geometry
    angle = x[drawn] / g.px_per_unit  # rad: the columns are the knob's angles
    assert angle.min() >= -0.05 and angle.max() <= np.pi / 2 + 0.05
    assert angle.max() - angle.min() > 1.0  # the hand turned it through most of the 90 degrees
    # where the design is inside the device's range the rendering follows it, angle by angle
    design = 0.3 * np.sin(16.0 * angle)  # 8/pi cycles per radian
    inside = np.abs(design) < 0.1
    mid = 0.5 * (lows[drawn] + highs[drawn])
    np.testing.assert_allclose(mid[inside], design[inside], atol=0.02)
    assert "against the knob's angle" in curve.toolTip()
    win.grab().save("/tmp/rendered_position.png")


def test_drawing_costs_only_the_visible_columns_of_a_long_trace(qapp) -> None:
    from timeline.gui.geometry import Geometry
    from timeline.gui.rendered_overlay import curves as draw
    from timeline.gui.rendered_overlay import peaks_of
    from timeline.limits.rendered import Trace

    rate, seconds = 10_000.0, 600.0  # a 10-minute design
    time = np.arange(int(rate * seconds)) / rate
    rendered = MAX * np.sin(2 * np.pi * 5.0 * time)
    trace = Trace("drive", "mNm", 1e3, time, rendered, rendered, step=1.0 / rate)
    peaks = peaks_of(trace)
    p = edits.new_project()
    p, _ = edits.add_track(p, "drive")
    deep = Geometry(1e6)  # 100 px per sample: 6e8 px of scene
    (curve,) = draw(p, [trace], [peaks], deep)
    assert curve.boundingRect().width() == pytest.approx(deep.x(seconds), rel=1e-6)
    x, lows, highs = curve.columns(deep.x(300.0), deep.x(300.0) + 1500.0)  # one screen at 5 min
    assert 15 <= len(x) <= 17  # the 16 samples under 1,500 px, each its own column
    np.testing.assert_allclose(highs, MAX * np.sin(2 * np.pi * 5.0 * x / deep.px_per_unit),
                               atol=1e-12)  # fmt: skip
    path = curve.path(deep.x(300.0), deep.x(300.0) + 1500.0)
    assert path.elementCount() == len(x)
    whole = Geometry(1500.0 / seconds)  # the whole design on one screen
    (curve,) = draw(p, [trace], [peaks], whole)
    x, lows, highs = curve.columns()
    assert len(x) == pytest.approx(1500, abs=2)
    assert highs.max() == pytest.approx(MAX, rel=1e-6) and lows.min() == pytest.approx(-MAX)
