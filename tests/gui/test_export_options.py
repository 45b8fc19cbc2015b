"""File > Export writes what the CLI's export writes: the umask's mode, --rate, --fixed-point."""

from __future__ import annotations

import json
import os
import stat
from pathlib import Path

import pytest

from timeline import edits
from timeline.files import exporting, projectfile
from timeline.gui.export_options import ExportOptions


def mode(path) -> int:
    return stat.S_IMODE(os.stat(path).st_mode)


@pytest.mark.parametrize("umask", [0o022, 0o077, 0o002])
def test_a_gui_export_follows_the_umask_like_the_cli(window, qtbot, tmp_path, umask):
    old = os.umask(umask)
    try:
        window.export_to(tmp_path / "gui.csv")
        qtbot.waitUntil(lambda: not window.jobs, timeout=20_000)
        exporting.export_project(window.doc.project, tmp_path / "cli.csv")
    finally:
        os.umask(old)
    assert mode(tmp_path / "gui.csv") == mode(tmp_path / "cli.csv") == 0o666 & ~umask


def test_a_gui_export_over_a_file_keeps_its_mode(window, qtbot, tmp_path):
    target = tmp_path / "kept.csv"
    target.write_text("old")
    target.chmod(0o640)
    window.export_to(target)
    qtbot.waitUntil(lambda: not window.jobs, timeout=20_000)
    assert mode(target) == 0o640 and target.read_text() != "old"


def test_the_dialog_gives_the_clis_rate_and_fixed_point(window, qtbot, tmp_path):
    target = tmp_path / "knob.json"
    dialog = ExportOptions(window.doc.project, target, window)
    qtbot.addWidget(dialog)
    assert dialog.options() == {}  # the tables' default rate, float tables: the CLI's defaults
    assert dialog.rate.value() == 1000.0  # firmware tables: one entry per millisecond
    dialog.rate.setValue(2000.0)
    dialog.fixed_point.setChecked(True)
    assert dialog.options() == {"rate": 2000.0, "fixed_point": True}
    window.export_to(target, **dialog.options())
    qtbot.waitUntil(lambda: not window.jobs, timeout=20_000)
    tables = json.loads(target.read_text())
    cli = tmp_path / "cli.json"
    exporting.export_project(window.doc.project, cli, rate=2000.0, fixed_point=True)
    assert tables == json.loads(cli.read_text())
    found = json.dumps(tables)
    assert '"step": 0.0005' in found and '"count": 5001' in found and "int16" in found


def test_a_position_project_sets_the_step_in_degrees(qtbot, tmp_path):
    project = edits.new_project("position")
    dialog = ExportOptions(project, tmp_path / "knob.h")
    qtbot.addWidget(dialog)
    assert dialog.rate.value() == pytest.approx(0.01)  # the default: one value per 0.01 degree
    assert dialog.options() == {}
    dialog.rate.setValue(0.5)
    assert dialog.options()["rate"] == pytest.approx(180 / 3.141592653589793 / 0.5)
    assert ExportOptions(project, tmp_path / "knob.csv").fixed_point.isEnabled() is False


def test_firmware_tables_start_at_one_entry_per_degree_and_show_their_size(qtbot, tmp_path):
    project = projectfile.load(Path(__file__).resolve().parents[2] / "projects" / "fan_knob.htl")
    dialog = ExportOptions(project, tmp_path / "fan.h")
    qtbot.addWidget(dialog)
    assert dialog.rate.value() == pytest.approx(1.0) and dialog.options() == {}
    said = dialog.table_size.text()
    assert said == "281 entries a table, end to end: 1,124 bytes each as float32"
    dialog.rate.setValue(0.5)
    dialog.fixed_point.setChecked(True)
    assert dialog.table_size.text() == "561 entries a table, end to end: 1,122 bytes each as int16"
