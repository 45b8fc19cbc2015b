"""The playback bench's probe: where every CPU's probe was overdue at once, the machine stopped."""

from __future__ import annotations

import pytest

from timeline.bench.machine_stall import longest_common


def test_the_machine_stopped_only_where_every_cpus_probe_was_overdue():
    cpu0 = [(1.000, 1.034), (2.000, 2.010)]
    cpu1 = [(1.004, 1.040), (3.000, 3.050)]  # its 50 ms alone: the other CPU ran
    assert longest_common([cpu0, cpu1]) == pytest.approx(0.030)


def test_no_common_overdue_interval_is_no_stop():
    assert longest_common([[(1.0, 1.1)], [(2.0, 2.1)]]) == 0.0
    assert longest_common([]) == 0.0
