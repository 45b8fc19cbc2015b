"""A LatenessMeter counts blocks later than the lead, gaps over 50 ms and the worst delay."""

from __future__ import annotations

import numpy as np
import pytest

from timeline.plugins.device_protocol import Lateness, LatenessMeter, Telemetry


def test_blocks_filling_the_lead_then_on_time_are_not_late():
    meter = LatenessMeter(lead=0.03, asked=99.99)
    for k in range(4):  # the first lead goes at once
        assert meter.handed(100.0 + 0.01 * k, 100.0) == 0.0
    for k in range(4, 10):  # then each 30 ms before it plays
        assert meter.handed(100.0 + 0.01 * k, 100.0 + 0.01 * k - 0.03) == pytest.approx(0.0)
    counts = meter.counts()
    assert (counts.blocks, counts.late, counts.gaps) == (10, 0, 0)
    assert counts.first_block == pytest.approx(0.01)
    assert counts.sentence() == ""


def test_a_stall_makes_the_blocks_after_it_late():
    meter = LatenessMeter(lead=0.03, asked=0.0)
    meter.handed(1.00, 1.00)
    meter.handed(1.01, 1.00)
    # 120 ms with nothing, then the next three blocks at once
    delays = [meter.handed(1.00 + 0.01 * k, 1.12) for k in (2, 3, 4)]
    assert delays == pytest.approx([0.12, 0.12, 0.11])
    counts = meter.counts()
    assert (counts.blocks, counts.late, counts.gaps) == (5, 3, 1)
    assert counts.worst == pytest.approx(0.12)
    assert counts.sentence() == (
        "3 blocks late, worst 120 ms, 1 gap over 50 ms: the knob may have gone slack"
    )


def test_one_late_block_is_named_in_the_singular():
    assert Lateness(blocks=10, late=1, worst=0.062).sentence() == (
        "1 block late, worst 62 ms: the knob may have gone slack"
    )


def test_the_play_summary_names_the_late_blocks():
    n = 10
    z = np.zeros(n)
    counts = Lateness(blocks=203, late=2, gaps=1, worst=0.0415, first_block=0.004)
    tel = Telemetry(1e4, np.arange(n) / 1e4, z, z, z, z, np.zeros(n, bool), lateness=counts)
    assert tel.summary()[-1] == (
        "real time: 2 of 203 blocks later than the 30 ms lead, 1 gaps over 50 ms, worst 41.5 ms "
        "behind, first block 4 ms"
    )
    assert Telemetry.concatenate([tel, tel]).lateness == counts
