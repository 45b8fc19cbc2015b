"""A table at 1e9 Hz played at 10 Hz: every source sample falls in one output step, which holds
their sum over the step (a box average), found without soxr's filter for a 1e-8 ratio (that took
minutes and gigabytes)."""

from __future__ import annotations

import numpy as np

from timeline.signal.render_presets import preset
from timeline.tiles import SampledTile


def test_a_billion_hertz_table_at_ten_hertz_is_its_area_in_the_first_step():
    tile = SampledTile(np.array([1.0, -2.0, 3.0]), 1e9, "fast")
    values = tile.render(0.0, 0.1, 20, preset("normal"))
    step = 1e9 * 0.1  # source samples per output sample
    assert abs(values[0] - (1.0 - 2.0 + 3.0) / step) <= 1e-15 * 2 / step
    assert not values[1:].any() and np.isfinite(values).all()


def test_a_million_to_one_step_is_a_box_average_too():
    """A 100-sample AIFF at 1e9 Hz in a 1 kHz project (found by the hostile campaign): soxr's
    filter for a 1e6 ratio ran 52 s; the step's sum is the box average's value exactly."""
    data = np.arange(1.0, 101.0) / 100  # sums to 50.5
    values = SampledTile(data, 1e9, "fast").render(0.0, 1e-3, 3, preset("normal"))
    assert abs(values[0] - 50.5e-6) <= 1e-18 and not values[1:].any()
