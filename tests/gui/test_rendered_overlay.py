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
    g = win.view.geometry
    first = next(c for c in curves(win) if c.lane == 0)
    assert first.highs.max() == pytest.approx(MAX) and first.lows.min() == pytest.approx(-MAX)
    box = first.path().boundingRect()
    assert box.top() == pytest.approx(level_y(g, 0, 1.0))  # flat at full scale, not above it
    assert box.bottom() == pytest.approx(level_y(g, 0, -1.0))
    assert box.left() == pytest.approx(0.0) and box.right() == pytest.approx(g.x(2.5), abs=1.0)
    assert len(first.highs) == pytest.approx(g.x(2.5), abs=2)  # one column per pixel
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
    from timeline.devices import Hand, open_device
    from timeline.gui.geometry import Geometry
    from timeline.gui.rendered_overlay import curves as draw
    from timeline.limits.actuators import actuator
    from timeline.limits.plot import traces

    project, _ids = two_track_project()
    with open_device("sim") as sim:
        info = replace(sim.info, actuator=actuator("lra-175"))
    lra, knob = traces(project, info, info.actuator, Hand("hold"), "normal")
    assert lra.designed.max() == pytest.approx(MAX) and knob.rendered.max() == pytest.approx(MAX)
    assert lra.rendered.max() < 0.01 * MAX  # a 5 Hz sine and a 2 Hz ramp, far below 175 Hz
    items = draw(project, [lra, knob], Geometry(200.0))
    assert [(c.lane, c.trace.label) for c in items] == [
        (0, "drive on lra-175"), (1, "drive on lra-175"),
        (0, "torque on sim, hand hold"), (1, "torque on sim, hand hold"),
    ]  # fmt: skip
    assert items[0].pen().color() != items[2].pen().color()
    assert items[0].highs.max() < 0.01 * MAX and items[2].highs.max() == pytest.approx(MAX)
