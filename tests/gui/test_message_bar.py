"""A long message is never cut: elided on its one line, the whole sentence in the tooltip."""

from __future__ import annotations

LONG = (
    "cannot write /home/designer/projects/fan-knob/exports/a very long folder name/"
    "fan_knob_final_v3.h: the folder /home/designer/projects/fan-knob/exports/a very long "
    "folder name is not writable; choose another folder or change its permissions and export "
    "the design again"
)


def test_a_long_message_is_elided_with_the_whole_in_the_tooltip(window, qtbot):
    window.resize(1024, 768)
    qtbot.waitUntil(lambda: window.width() == 1024)
    bar = window.messages
    height = window.statusBar().height()
    bar.show_message(LONG, "error")
    qtbot.wait(10)
    shown = bar.label.text()
    assert shown.endswith("…") and LONG.startswith(shown[:-1])
    assert bar.label.fontMetrics().horizontalAdvance(shown) <= bar.label.width()
    assert bar.label.toolTip() == LONG == bar.text
    assert window.statusBar().height() == height  # one line: the lanes do not jump

    window.resize(2400, 768)  # room for the whole
    qtbot.waitUntil(lambda: window.width() == 2400)
    assert bar.label.text() == LONG and bar.label.toolTip() == ""


def test_the_message_bar_does_not_widen_the_window(window):
    window.messages.show_message(LONG * 3, "error")
    assert window.messages.minimumSizeHint().width() < 300
    assert window.minimumSizeHint().width() <= 1024
