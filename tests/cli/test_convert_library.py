"""`convert` of a loud sound passes `check`; many sounds or a folder convert in one process."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import soundfile as sf

from tests.analysis.conftest import tone_bursts
from timeline.cli.main import main
from timeline.files import projectfile
from timeline.limits.check import check
from timeline.plugins.device_protocol import open_device

RATE = 16_000


def write(path: Path, level: float) -> Path:
    sf.write(path, level * tone_bursts([0.05, 0.3], 150.0, 0.5, rate=RATE), RATE, subtype="FLOAT")
    return path


def test_a_loud_sound_converts_within_the_default_device_s_limit(tmp_path: Path) -> None:
    out = tmp_path / "loud.htl"
    assert main(["convert", str(write(tmp_path / "loud.wav", 1.25)), "-o", str(out)]) == 0
    with open_device("sim") as device:
        report = check(projectfile.load(out), device.info)
    assert "torque-saturation" not in report.kinds() and "below-detection" not in report.kinds()
    # at the sound's own level and no staging, the same design saturates the knob
    over = tmp_path / "over.htl"
    assert main(["convert", str(tmp_path / "loud.wav"), "-o", str(over), "--gain", "0"]) == 0
    with open_device("sim") as device:
        assert "torque-saturation" in check(projectfile.load(over), device.info).kinds()


def test_a_folder_of_sounds_becomes_a_folder_of_designs(tmp_path: Path, capsys) -> None:
    sounds = tmp_path / "sounds"
    sounds.mkdir()
    for k, level in enumerate([1.0, 0.5, 0.002]):
        write(sounds / f"s{k}.wav", level)
    (sounds / "readme.txt").write_text("not a sound")
    out = tmp_path / "designs"
    assert main(["convert", str(sounds), "-o", str(out), "--format", "ahap", "--jobs", "2"]) == 0
    assert sorted(p.name for p in out.iterdir()) == ["s0.ahap", "s1.ahap", "s2.ahap"]
    for path in out.iterdir():
        events = json.loads(path.read_text())["Pattern"]
        assert any("Event" in e for e in events)
    err = capsys.readouterr().err
    assert "converted 3 of 3 sounds" in err and "note: s2.wav: raised" in err
    # a sound that fails is one sentence, the others are still written
    (sounds / "broken.wav").write_text("not a sound")
    assert main(["convert", str(sounds), "-o", str(out), "--jobs", "1"]) == 1
    assert "broken.wav" in capsys.readouterr().err
    assert np.all([(out / f"s{k}.haptic").is_file() for k in range(3)])
