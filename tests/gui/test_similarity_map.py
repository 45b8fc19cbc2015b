"""The similarity map opened from the Variants menu, as a person does."""

from __future__ import annotations

import pytest

from timeline import edits


def _menu_action(win, text: str):
    return next(a for a in win.findChildren(type(win.menuBar().actions()[0]))
                if a.text() == text)  # fmt: skip


def test_map_of_variants_shows_the_pairs_too_alike(window, qtbot) -> None:
    win = window
    clip = win.ids["c1"]
    p = edits.save_variant(win.doc.project, "A")
    p = edits.set_clip_gain(p, clip, 10 ** (1 / 20))  # 1 dB: below the 2.2 dB JND
    p = edits.save_variant(p, "B")
    p = edits.set_clip_gain(p, clip, 3.0)  # 9.5 dB
    p = edits.save_variant(p, "C")
    win.doc.replace("variants", p)
    _menu_action(win, "&Map of variants by feel…").trigger()
    panel = win.similarity_maps[-1]
    qtbot.addWidget(panel)
    qtbot.waitExposed(panel)
    c = panel.canvas.comparison
    assert c.names == ["A", "B", "C"]
    assert [(a, b) for a, b, _ in c.too_alike()] == [("A", "B")]
    assert c.matrix[0, 1] == pytest.approx(1 / 2.2, abs=0.02)
    assert panel.table.item(0, 2).text() == f"{c.matrix[0, 2]:.2f}"
    assert "Too alike: A and B" in panel.status.text()
    points = panel.canvas.points()
    gap = (points["A"] - points["C"]).manhattanLength()
    assert gap > 5 * (points["A"] - points["B"]).manhattanLength()
    panel.grab().save("/tmp/similarity_map.png")


def test_map_of_a_palette_tab_and_a_refusal(window, qtbot) -> None:
    win = window
    _menu_action(win, "Palette &tab by feel…").trigger()
    panel = win.similarity_maps[-1]
    qtbot.addWidget(panel)
    assert len(panel.canvas.comparison.names) >= 10  # the Templates tab
    _menu_action(win, "&Map of variants by feel…").trigger()  # no variants saved
    empty = win.similarity_maps[-1]
    qtbot.addWidget(empty)
    assert empty.status.text().startswith("Cannot compare:")
