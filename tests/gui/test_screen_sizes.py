"""The editor on a laptop's screen: narrow enough, every control inside the window, no jumps."""

from __future__ import annotations

import pytest
from PySide6.QtCore import QRect
from PySide6.QtWidgets import QWidget

SIZES = [(1280, 800), (1600, 1000)]


def controls(win) -> dict[str, QWidget]:
    """The transport's play, hand and playhead controls, and the scope."""
    t = win.transport
    return {
        "play": t.play_button,
        "loop": t.loop,
        "selected tracks": t.selected_only,
        "playhead": t.where,
        "device": t.device,
        "hand model": t.hand_model,
        "hand": t.hand,
        "hand value": t.hand_value,
        "scope": t.scope,
    }


def wholly_shown(win, widget: QWidget) -> bool:
    """Visible, inside the window, and not clipped by any pane it sits in."""
    if not widget.isVisible():
        return False
    top_left = widget.mapTo(win, widget.rect().topLeft())
    if not win.rect().contains(QRect(top_left, widget.size())):
        return False
    return widget.visibleRegion().boundingRect() == widget.rect()


def test_the_window_is_at_most_1024_pixels_wide_at_its_narrowest(window, qtbot):
    window.sound_import.dock.show()  # the Sound analysis dock too
    window.transport.hand.setCurrentText("turn")
    window.doc.select_clips([window.ids["c1"]])
    window.doc.select_tile(window.ids["sine"])
    qtbot.wait(10)
    assert window.minimumSizeHint().width() <= 1024
    assert window.minimumSize().width() <= 1024


@pytest.mark.parametrize(("width", "height"), SIZES)
@pytest.mark.parametrize("hand", ["hold", "turn", "push"])
@pytest.mark.parametrize("dock", [False, True], ids=["", "dock"])
def test_every_transport_control_is_inside_the_window(window, qtbot, width, height, hand, dock):
    window.sound_import.dock.setVisible(dock)
    window.doc.select_clips([window.ids["c1"]])
    window.doc.select_tile(window.ids["sine"])
    window.resize(width, height)
    window.transport.hand.setCurrentText(hand)
    qtbot.waitUntil(lambda: window.width() == width and window.height() == height)
    qtbot.wait(10)
    shown = controls(window)
    if hand == "hold":
        del shown["hand value"]  # no speed or torque to set while the hand holds
    hidden = [name for name, widget in shown.items() if not wholly_shown(window, widget)]
    assert hidden == []
    dock_name = "-dock" if dock else ""
    window.grab().save(f"/tmp/ed-screen-{width}x{height}-{hand}{dock_name}.png")


def test_the_panes_keep_their_widths_when_the_inspector_fills(window, qtbot):
    window.resize(1280, 800)
    qtbot.wait(10)
    before = window.bottom_split.sizes()
    window.doc.select_clips([window.ids["c1"]])
    window.doc.select_tile(window.ids["sine"])
    window.transport.hand.setCurrentText("turn")
    qtbot.wait(10)
    assert window.bottom_split.sizes() == before
