"""The distance matrix taken for all pairs at once equals the one-pair formula (parts()) pair by
pair, on a set of icons that differ in every feature, force layers present in some only."""

from __future__ import annotations

import math

import numpy as np
import pytest

from timeline import edits, generator
from timeline.errors import HapticTimelineError
from timeline.limits.design import sample
from timeline.similarity.distance import distances, parts
from timeline.similarity.features import FLOOR_DB, features


def icon(frequency: float, pulses: int, seconds: float, layers: tuple[str, ...] = ()):
    p = edits.new_project("time")
    p, drive = edits.add_track(p, "drive", "drive")
    p, tone = edits.add_tile(p, generator("sine", seconds, "tone", frequency=frequency))
    for i in range(pulses):
        p, _ = edits.add_clip(p, drive, tone, i * (seconds + 0.04 * (i + 1)), gain=0.3 + 0.1 * i)
    for n, kind in enumerate(layers):
        p, track = edits.add_track(p, kind, kind)
        p, level = edits.add_tile(p, generator("constant", seconds * (n + 1), "level", value=1.0))
        p, _ = edits.add_clip(p, track, level, 0.02, gain=0.5 / (n + 1))
    return p


ICONS = [
    ("plain", icon(175.0, 1, 0.3)),
    ("twice", icon(175.0, 2, 0.2)),
    ("thrice", icon(90.0, 3, 0.1, ("stiffness",))),
    ("low", icon(30.0, 1, 0.6, ("damping", "stiffness"))),
    ("long", icon(250.0, 4, 0.15, ("mass",))),
    ("twice again", icon(175.0, 2, 0.2)),
]


def test_every_pair_equals_the_one_pair_formula():
    measured = [features(name, sample(p, None, "normal")) for name, p in ICONS]
    matrix, table = distances(measured)
    floor = FLOOR_DB
    assert len(table) == len(ICONS)
    for i, a in enumerate(measured):
        assert table[i][i] == {} and matrix[i, i] == 0.0
        for j, b in enumerate(measured):
            if i == j:
                continue
            expected = parts(a, b, floor)
            assert table[i][j] == pytest.approx(expected, rel=1e-12, abs=1e-12)
            total = math.sqrt(sum(v * v for v in expected.values()))
            assert matrix[i, j] == pytest.approx(total, rel=1e-12, abs=1e-12)
    assert matrix[1, 5] == 0.0  # the same icon twice
    assert min(table[0][j]["force"] for j in (2, 3, 4)) > 0  # a layer one icon lacks counts


def test_icons_of_two_axes_are_refused_naming_the_first_pair():
    knob = edits.new_project("position")
    knob, track = edits.add_track(knob, "torque", "torque")
    knob, tile = edits.add_tile(knob, generator("sine", 1.0, "detents", frequency=4.0))
    knob, _ = edits.add_clip(knob, track, tile, 0.0)
    measured = [features(n, sample(p, None, "normal")) for n, p in [*ICONS[:2], ("knob", knob)]]
    with pytest.raises(HapticTimelineError, match="plain is a time icon and knob a position"):
        distances(measured)


def test_the_percentile_from_one_sort_is_numpys():
    from timeline.similarity.distance import PERCENTILE, _percentile_of_rows

    rng = np.random.default_rng(2)
    rows = np.abs(rng.standard_normal((500, 64)) * rng.uniform(0.0, 1e3, (500, 1)))
    np.testing.assert_allclose(
        _percentile_of_rows(rows), np.percentile(rows, PERCENTILE, axis=-1), rtol=1e-15, atol=0
    )
    assert _percentile_of_rows(np.zeros((2, 64))).tolist() == [0.0, 0.0]
