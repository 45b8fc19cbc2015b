"""A pair's distance is the same in any set; any order of kinds compares."""

from __future__ import annotations

from tests.similarity.test_compare import buzz
from timeline.similarity.compare import compare


def test_a_pair_is_as_far_apart_beside_a_louder_icon() -> None:
    soft, softer = buzz(gain=0.01), buzz(gain=0.01 * 10 ** (-30 / 20))
    alone = compare([("a", soft), ("b", softer)]).matrix[0, 1]
    beside = compare([("a", soft), ("b", softer), ("loud", buzz(gain=1.0))]).matrix[0, 1]
    assert alone == beside and alone > 5.0  # 30 dB apart, above the fixed floor


def test_a_spring_before_a_drive_compares_both_ways() -> None:
    spring, drive = buzz(kind="stiffness", shape="level"), buzz()
    forward = compare([("spring", spring), ("drive", drive)]).matrix[0, 1]
    backward = compare([("drive", drive), ("spring", spring)]).matrix[0, 1]
    assert forward == backward > 1.0
