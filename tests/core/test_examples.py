"""The committed example projects are exactly what projects/build_examples.py builds."""

import importlib.util
from pathlib import Path

import pytest

from timeline import render
from timeline.files import projectfile

PROJECTS = Path(__file__).resolve().parents[2] / "projects"
spec = importlib.util.spec_from_file_location("build_examples", PROJECTS / "build_examples.py")
build_examples = importlib.util.module_from_spec(spec)
spec.loader.exec_module(build_examples)


@pytest.mark.parametrize("name", sorted(build_examples.EXAMPLES))
def test_committed_file_matches_the_build_script(name):
    built = projectfile.dumps(build_examples.EXAMPLES[name]())
    assert (PROJECTS / name).read_text() == built, "run python projects/build_examples.py"


def test_fan_knob_torque_has_walls_and_four_detents():
    import numpy as np

    p = projectfile.load(PROJECTS / "fan_knob.htl")
    rate = 100 / np.radians(1)  # 100 samples per degree
    layers = render(p, 0.0, np.radians(280), rate)
    torque = layers["torque"]
    deg = np.arange(len(torque)) / 100
    # the walls push at 0.8 of full torque at their ends (below the delayed passivity bound)
    assert torque[deg == 0][0] == pytest.approx(0.144)  # lower wall pushes up
    assert torque[np.isclose(deg, 279.99)][0] == pytest.approx(-0.144, rel=1e-3)
    inside = (deg > 21) & (deg < 259)
    falling = np.flatnonzero((torque[:-1] > 0) & (torque[1:] <= 0) & inside[:-1])
    np.testing.assert_allclose(deg[falling], [50, 110, 170, 230], atol=0.02)
    assert layers["damping"][deg == 100][0] < layers["damping"][deg == 10][0]
    assert np.all(layers["mass"] == layers["mass"][0])
