"""Perceptual distances in JNDs, the MDS map, and the `compare` verb."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from timeline import edits, generator, save
from timeline.cli import main as cli
from timeline.similarity.compare import compare
from timeline.similarity.distance import RHYTHM_EVENT
from timeline.similarity.mds import classical_mds


def buzz(frequency=175.0, gain=0.5, seconds=0.3, pulses=1, kind="drive", shape="sine"):
    """`pulses` equal bursts of a tone (or constant levels on another kind), 50 ms apart."""
    p = edits.new_project("time")
    p, track = edits.add_track(p, kind, kind)
    tile = (
        generator("sine", seconds, "tone", frequency=frequency)
        if shape == "sine"
        else generator("constant", seconds, "level", value=1.0)
    )
    p, tile_id = edits.add_tile(p, tile)
    for i in range(pulses):
        p, _ = edits.add_clip(p, track, tile_id, i * (seconds + 0.05), gain=gain)
    return p


def parts(a, b) -> dict[str, float]:
    return compare([("a", a), ("b", b)]).parts[0][1]


def test_identical_icons_are_zero_apart() -> None:
    result = compare([("a", buzz()), ("b", buzz())])
    assert result.matrix[0, 1] == 0.0 and result.too_alike() == [("a", "b", 0.0)]


def test_each_feature_is_measured_in_its_jnd() -> None:
    louder = parts(buzz(gain=0.5), buzz(gain=0.5 * 10 ** (4.4 / 20)))
    assert louder["envelope"] == pytest.approx(2.0, abs=0.02)  # 4.4 dB = 2 amplitude JNDs
    assert louder["frequency"] == pytest.approx(0.0, abs=1e-3)
    higher = parts(buzz(frequency=100.0), buzz(frequency=118.0))
    assert higher["frequency"] == pytest.approx(1.0, abs=0.01)  # Weber 0.18
    longer = parts(buzz(seconds=0.5), buzz(seconds=0.5 * 1.16 * 1.16))
    assert longer["duration"] == pytest.approx(2.0, abs=0.01)  # Weber 0.16
    assert parts(buzz(pulses=2), buzz(pulses=3))["rhythm"] == pytest.approx(RHYTHM_EVENT)


def test_a_force_profile_is_measured_in_force_jnds() -> None:
    spring = parts(buzz(kind="stiffness", shape="level"), buzz(kind="stiffness", shape="level",
                                                               gain=0.5 / 0.93))  # fmt: skip
    assert spring["force"] == pytest.approx(1.0, abs=0.01)  # 7 % of the larger


def test_amplitude_modulation_is_rough() -> None:
    smooth = compare([("s", buzz(frequency=250.0)), ("s2", buzz(frequency=250.0))]).features[0]
    p = edits.new_project("time")
    p, track = edits.add_track(p, "drive", "drive")
    p, tile = edits.add_tile(p, generator("am", 0.3, "rough", carrier=250.0, modulation=40.0,
                                          depth=0.9))  # fmt: skip
    p, _ = edits.add_clip(p, track, tile, 0.0, gain=0.5)
    rough = compare([("r", p), ("s", buzz(frequency=250.0))]).features[0]
    assert smooth.roughness < 0.1 < 1.0 < rough.roughness


def test_mds_recovers_a_known_layout() -> None:
    points = np.array([[0.0, 0.0], [3.0, 0.0], [0.0, 4.0], [1.0, 1.0]])
    d = np.linalg.norm(points[:, None] - points[None], axis=2)
    coords, kept = classical_mds(d)
    assert kept == pytest.approx(1.0)
    np.testing.assert_allclose(np.linalg.norm(coords[:, None] - coords[None], axis=2), d,
                               atol=1e-9)  # fmt: skip


def test_compare_writes_the_matrix_and_the_map(tmp_path: Path, capsys) -> None:
    files = []
    for name, project in [("soft", buzz(gain=0.3)), ("soft2", buzz(gain=0.31)),
                          ("high", buzz(frequency=300.0)), ("triple", buzz(pulses=3))]:  # fmt: skip
        files.append(str(tmp_path / f"{name}.htl"))
        save(project, files[-1])
    png = tmp_path / "map.png"
    assert cli.main(["compare", *files, "--json", "--plot", str(png)]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["icons"] == ["soft", "soft2", "high", "triple"]
    d = np.array(out["distance"])
    assert d.shape == (4, 4) and np.allclose(d, d.T) and (np.diag(d) == 0).all()
    assert [a[:2] for a in out["too_alike"]] == [["soft", "soft2"]]
    assert d[0, 1] == pytest.approx(20 * math.log10(0.31 / 0.3) / 2.2, abs=0.01)
    xy = np.array(out["map"])
    assert np.linalg.norm(xy[2] - xy[3]) == pytest.approx(d[2, 3], rel=0.2)
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 10_000


def test_one_project_compares_its_variants(capsys) -> None:
    examples = Path(__file__).resolve().parents[2] / "projects"
    assert cli.main(["compare", str(examples / "notification_buzz.htl")]) == 0
    out = capsys.readouterr().out
    assert "B: stronger tap" in out and "too alike" not in out  # 3.5 dB on the tap: 1.6 JND
    assert cli.main(["compare", str(examples / "rising_resistance.htl")]) == 1
    assert "needs two icons" in capsys.readouterr().err


def test_a_slow_alternation_is_not_a_constant() -> None:
    p = edits.new_project("time")
    p, track = edits.add_track(p, "drive", "drive")
    p, tile = edits.add_tile(p, generator("square", 1.0, "5 Hz", frequency=5.0))
    p, _ = edits.add_clip(p, track, tile, 0.0, gain=0.5)
    square = compare([("square", p), ("level", buzz(shape="level", seconds=1.0))])
    assert square.features[0].frequency == pytest.approx(5.0, rel=0.05)  # longer than a frame
    assert square.parts[0][1]["frequency"] > 5.0
