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


def test_a_check_ending_after_a_failure_does_not_replace_it(window, qtbot, monkeypatch):
    from timeline.gui import message_bar

    monkeypatch.setattr(message_bar, "HOLD_SECONDS", 0.3)
    win, bar = window, window.messages
    qtbot.waitUntil(lambda: win.findings.settled, timeout=20_000)
    failed = "Import of long.wav failed: ValueError: column 3 is not a number"
    bar.show_message(failed, "error")
    win.findings.report = None  # the next check's summary is news again
    win.findings.schedule()
    qtbot.waitUntil(lambda: win.findings.settled and bar._pending is not None, timeout=20_000)
    assert bar.text == failed and bar.history[-1] == (failed, "error")
    # once the hold is up, the routine status follows
    qtbot.waitUntil(lambda: bar.text == "No device or perception limit crossed", timeout=5_000)
    assert bar.history[-2:] == [
        (failed, "error"),
        ("No device or perception limit crossed", "info"),
    ]


def test_routine_status_held_back_is_dropped_when_another_message_comes(window, qtbot, monkeypatch):
    from timeline.gui import message_bar

    monkeypatch.setattr(message_bar, "HOLD_SECONDS", 0.1)
    bar = window.messages
    bar.show_message("undid move 'sine' to 1 s", hold=True)
    bar.show_routine("No device or perception limit crossed")
    assert bar.text == "undid move 'sine' to 1 s"
    bar.show_message("move clip (Ctrl+Z undoes)")  # not held: routine status may replace it
    qtbot.wait(300)
    assert bar.text == "move clip (Ctrl+Z undoes)"
    bar.show_routine("1 limit(s) crossed: stiffness-limit", "finding")
    assert bar.text == "1 limit(s) crossed: stiffness-limit"


def test_undo_is_held_against_a_late_check(window, qtbot):
    win = window
    qtbot.waitUntil(lambda: win.findings.settled, timeout=20_000)
    p = win.doc.project
    win.doc.replace("nudge", p)
    win.doc.undo()
    win.findings.report = None
    win.findings.schedule()
    qtbot.waitUntil(lambda: win.findings.settled, timeout=20_000)
    assert win.messages.text == "undid nudge"
