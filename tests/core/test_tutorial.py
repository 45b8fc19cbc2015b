"""docs/tutorial.md runs as written: its Python and shell blocks in order, and the output shown."""

import json
import math
import re
import shlex
from pathlib import Path

import numpy as np
import pytest

from timeline.cli.main import main
from timeline.files import projectfile
from timeline.rendering.playback import position_table, rest_angles

ROOT = Path(__file__).resolve().parents[2]
DOC = ROOT / "docs" / "tutorial.md"
BLOCK = re.compile(r"```(python|sh|text)\n(.*?)```", re.S)


def blocks() -> list[tuple[str, str]]:
    """The tutorial's fenced blocks in order: (language, text)."""
    return BLOCK.findall(DOC.read_text())


def run_line(line: str, capsys) -> str:
    """Run one `haptic-timeline ...` line in-process; its stdout. `# exit N` says the status."""
    command, _, comment = line.partition("#")
    expected = int(re.fullmatch(r"\s*exit (\d+)\s*", comment).group(1)) if comment else 0
    argv = shlex.split(command)
    assert argv[0] == "haptic-timeline", line
    capsys.readouterr()
    assert main(argv[1:]) == expected, line
    return capsys.readouterr().out


def test_tutorial_runs_and_shows_what_it_says(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    namespace: dict = {}
    shown = ""
    found = blocks()
    assert [lang for lang, _ in found].count("sh") >= 6
    for lang, text in found:
        if lang == "python":
            exec(compile(text, str(DOC), "exec"), namespace)
        elif lang == "sh":
            shown = "".join(run_line(line, capsys) for line in text.splitlines() if line.strip())
        else:  # the output the tutorial shows is what the block before it printed
            printed = [line.strip() for line in shown.splitlines()]
            for line in text.splitlines():
                if line.strip() not in ("", "..."):
                    assert line.strip() in printed, line

    # part 1: the fan knob rests at Off, Lo, Med and Hi, and is the shipped example
    table, _ = position_table(namespace["fan"])
    np.testing.assert_allclose(np.degrees(rest_angles(table)), [50, 110, 170, 230], atol=0.01)
    shipped, _ = position_table(projectfile.load(ROOT / "projects" / "fan_knob.htl"))
    for layer in ("torque", "damping", "mass"):
        np.testing.assert_allclose(getattr(table, layer), getattr(shipped, layer), atol=1e-12)
    assert table.torque[0] == pytest.approx(0.8 * 0.18)  # the lower wall pushes up at 0 degrees
    assert "#define FAN_TABLES_COUNT 281" in (tmp_path / "fan_tables.h").read_text()

    # part 2: the buzz at 0.25 s is the sine at track gain 0.5, computed here independently
    drive = namespace["drive_torque"]
    assert drive[2500] == pytest.approx(0.5 * 0.18 * math.sin(2 * math.pi * 175 * 0.25))
    assert drive[2500] == pytest.approx(-0.09)
    assert np.abs(drive).max() == pytest.approx(0.16198, abs=1e-5)  # emphasis on the sine
    assert json.loads((tmp_path / "buzz.ahap").read_text())["Version"] == 1.0
    for made in ("fan.png", "buzz.png", "buzz.wav"):
        assert (tmp_path / made).stat().st_size > 1000


def test_tutorial_pictures_exist_and_are_small():
    pictures = re.findall(r"\]\((img/[^)]+\.png)\)", DOC.read_text())
    assert len(pictures) >= 5
    for picture in pictures:
        path = DOC.parent / picture
        assert path.stat().st_size < 150_000, picture
