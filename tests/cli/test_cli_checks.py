"""The CLI checks what it can before doing slow work: outputs, verbs, and import positions."""

import shutil

import pytest

from timeline.cli import main as cli
from timeline.files import projectfile

EXAMPLE = "projects/notification_buzz.htl"


def _one_line_error(capsys) -> str:
    err = capsys.readouterr().err
    assert err.count("\n") == 1, err
    return err


def test_a_mistyped_verb_is_an_unknown_verb(capsys):
    assert cli.main(["frobnicate"]) == 2
    err = _one_line_error(capsys)
    assert "unknown verb 'frobnicate'" in err and "display" not in err


def test_a_close_verb_is_suggested(capsys):
    assert cli.main(["rendr", "x.htl"]) == 2
    assert "did you mean 'render'?" in _one_line_error(capsys)


@pytest.mark.parametrize("name", ["design.htl", "some/dir/design"])
def test_a_project_path_still_opens_the_editor(name):
    assert cli._with_default_verb([name], {"edit"}) == ["edit", name]


def test_play_refuses_an_unknown_plot_type_before_playing(tmp_path, capsys):
    plot = tmp_path / "out.xyz"
    assert cli.main(["play", EXAMPLE, "--plot", str(plot), "--duration", "0.01"]) == 1
    captured = capsys.readouterr()
    assert "--plot cannot write .xyz files" in captured.err and "png" in captured.err
    assert captured.out == "" and "playing" not in captured.err  # nothing was played
    assert not plot.exists()


def test_play_refuses_a_missing_output_folder_before_playing(tmp_path, capsys):
    out = tmp_path / "missing" / "x.csv"
    assert cli.main(["play", EXAMPLE, "-o", str(out), "--duration", "0.01"]) == 1
    captured = capsys.readouterr()
    assert f"the folder {out.parent} does not exist" in captured.err
    assert captured.out == "" and "playing" not in captured.err


def test_import_before_the_timeline_starts_is_refused(tmp_path, capsys):
    project = tmp_path / "p.htl"
    shutil.copy(EXAMPLE, project)
    before = project.read_bytes()
    source = tmp_path / "x.csv"
    source.write_text("time,value\n0,0\n0.001,0.5\n0.002,1\n")
    assert cli.main(["import", str(source), "--into", str(project), "--at", "-1"]) == 1
    assert "cannot start at -1 s: the timeline starts at 0" in _one_line_error(capsys)
    assert project.read_bytes() == before
    assert cli.main(["import", str(source), "--into", str(project), "--at", "0.5"]) == 0
    starts = [c.start for t in projectfile.load(project).tracks for c in t.clips]
    assert 0.5 in starts
