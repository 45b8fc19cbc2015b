"""The mirror line without Alt (taken by window managers): Ctrl+Shift+click, or the clip menu."""

from __future__ import annotations

import pytest
from PySide6.QtCore import QPointF, Qt
from PySide6.QtTest import QTest

from .helpers import click, view_point
from .test_menus_and_readouts import choose, right_click

CTRL = Qt.KeyboardModifier.ControlModifier
SHIFT = Qt.KeyboardModifier.ShiftModifier
ALT = Qt.KeyboardModifier.AltModifier


def level_point(win, clip_id: str, value: float):
    """The viewport point in the clip's middle at a value of full scale."""
    item = win.view.clip_item(clip_id)
    y = item.mapToScene(QPointF(0, item.value_y(value))).y()
    return view_point(win, QPointF(win.view.clip_scene_rect(clip_id).center().x(), y))


def pivot(win, clip_id: str) -> float:
    return win.doc.project.find_clip(clip_id)[1].pivot


@pytest.mark.parametrize("mods", [CTRL | SHIFT, ALT], ids=["ctrl+shift", "alt"])
def test_a_click_with_ctrl_shift_or_alt_places_the_mirror_line(window, mods):
    c1 = window.ids["c1"]
    click(window, level_point(window, c1, 0.5), mods)
    assert pivot(window, c1) == pytest.approx(0.5, abs=0.05)
    assert window.doc.history.undo_label == "place mirror line"
    assert window.doc.selected_clips == [c1]


def test_ctrl_click_still_toggles_the_selection(window):
    c1, c2 = window.ids["c1"], window.ids["c2"]
    window.doc.select_clips([c2])
    click(window, level_point(window, c1, 0.5), CTRL)
    assert window.doc.selected_clips == [c2, c1]
    assert pivot(window, c1) == 0.0


def test_the_clip_menu_sets_the_mirror_line_where_it_was_opened(window, qtbot):
    c1 = window.ids["c1"]
    right_click(window, level_point(window, c1, -0.25))
    menu = window.view.menu
    qtbot.waitUntil(menu.isVisible)
    choose(menu, "Set &mirror line here")
    assert pivot(window, c1) == pytest.approx(-0.25, abs=0.05)
    assert len(window.doc.history) == 2  # one undo step
    QTest.keyClick(window, Qt.Key.Key_Z, CTRL)
    assert pivot(window, c1) == 0.0
