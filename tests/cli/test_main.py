"""The bare command and a bare project path open the editor; unknown flags are usage errors."""

import pytest

from timeline.cli import main as cli


@pytest.mark.parametrize(
    ("argv", "expected"),
    [
        ([], ["edit"]),
        (["projects/fan_knob.htl"], ["edit", "projects/fan_knob.htl"]),
        (["render", "a.htl", "-o", "a.csv"], ["render", "a.htl", "-o", "a.csv"]),
        (["--help"], ["--help"]),
    ],
)
def test_default_verb_is_edit(argv, expected):
    assert cli._with_default_verb(argv, {"edit", "render"}) == expected


def test_bare_project_without_a_display_says_so(monkeypatch, capsys):
    for name in ("DISPLAY", "WAYLAND_DISPLAY", "QT_QPA_PLATFORM"):
        monkeypatch.delenv(name, raising=False)
    assert cli.main(["projects/fan_knob.htl"]) == 1
    err = capsys.readouterr().err
    assert "no display" in err and "haptic-timeline play" in err and err.count("\n") == 1
