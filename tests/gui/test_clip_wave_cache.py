"""A clip keeps its wave's pixel columns while it is dragged along its lane, and draws them
again when anything but its start changes."""

from __future__ import annotations

from dataclasses import replace

from timeline.gui.clip_item import ClipItem
from timeline.gui.geometry import Geometry
from timeline.model import Clip
from timeline.tiles import generator


def test_a_moved_clip_reuses_its_wave_and_a_new_gain_redraws_it(qapp):
    geometry = Geometry()
    geometry.px_per_unit = 100.0
    tile = generator("sine", 1.0, frequency=5)
    clip = Clip("c1", "tile1", 0.5, 0.0, 1.0)
    item = ClipItem(geometry, clip, tile)

    def show(state: Clip) -> list:
        item.update_from(state, tile, "track1", 0, "#c05030", 1000.0, False)
        return item._wave_lines(0, 100)

    lines = show(clip)
    assert show(replace(clip, start=2.0)) is lines  # only the start changed
    quieter = show(replace(clip, start=2.0, gain=0.25))
    assert quieter is not lines
    height = [line.y2() - line.y1() for line in lines]
    assert max(line.y2() - line.y1() for line in quieter) < 0.5 * max(height)
