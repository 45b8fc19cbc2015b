"""The editor's readouts on a position project speak degrees (issue 22): the playhead, the
inspector's clip fields and a clip's tooltip."""

from __future__ import annotations

import math
from pathlib import Path

import pytest
from PySide6.QtCore import QPoint, Qt
from PySide6.QtTest import QTest

from timeline.files import projectfile
from timeline.gui.clip_item import clip_tip

from .helpers import click, clip_point, shown_window

FAN = Path(__file__).resolve().parents[2] / "projects" / "fan_knob.htl"


@pytest.fixture
def fan(qtbot):
    win = shown_window(qtbot, projectfile.load(FAN), 1280, 800)
    win.view.lane_geometry.px_per_unit = 150.0  # px per radian: the 240 deg detents ~630 px
    win.view.refresh()
    return win


def test_every_readout_of_the_fan_knob_is_in_degrees(fan):
    project = fan.doc.project
    detents = next(c for t in project.tracks for c in t.clips if c.id == "c22")  # 20 to 260 deg
    x = fan.ruler.x_of(math.radians(110))  # a click on the ruler moves the playhead there
    QTest.mouseClick(fan.ruler, Qt.MouseButton.LeftButton, pos=QPoint(round(x), 30))
    assert fan.transport.where.text() == f"{math.degrees(fan.ruler.u_of(round(x))):.1f}°"
    assert abs(float(fan.transport.where.text()[:-1]) - 110) < 0.5
    click(fan, clip_point(fan, detents.id))
    page = fan.inspector.pages["clip"]
    assert page.isVisible() and page.start.suffix() == "°"
    assert page.start.value() == pytest.approx(20.0)
    tile = project.tile(detents.tile_id)
    assert clip_tip(detents, tile, False, (), "position").splitlines()[0] == (
        "four detents: 20° to 260°"
    )
    length = page.length.value() if hasattr(page, "length") else None
    assert length is None or length == pytest.approx(240.0)
