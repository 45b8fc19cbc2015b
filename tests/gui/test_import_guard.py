"""The editor's import goes through the same guard as the command line's (issue 25)."""

from __future__ import annotations


def test_the_editor_refuses_an_import_placed_before_zero(window, qtbot, tmp_path):
    bad = tmp_path / "early.csv"
    bad.write_text("t,v\n-1,0.1\n-0.5,0.2\n0,0.3\n")
    before = window.doc.project
    window.import_files([bad], window.ids["t1"], 0.0)
    qtbot.waitUntil(lambda: not window.jobs, timeout=10_000)
    assert window.doc.project is before
    assert window.messages.text == (
        "early.csv cannot be imported: a clip would start at -1 s, before the timeline's 0"
    )
