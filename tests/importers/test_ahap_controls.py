"""A control curve that starts before the last one ended replaces it from there, found from the
points around its start (not an array of every point per curve: quadratic in curves)."""

from __future__ import annotations

import bisect

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from importers.ahap import _Control

unit = st.floats(0.0, 1.0).map(lambda v: round(v, 3))
curve = st.tuples(
    st.floats(0.0, 2.0).map(lambda t: round(t, 3)),
    st.lists(st.tuples(st.floats(0.0, 0.5).map(lambda t: round(t, 3)), unit), min_size=1),
)


def _set_from_whole_arrays(control: _Control, start: float, points) -> None:
    """The earlier set_from: the value before `start` from arrays of all points so far."""
    if start >= control._t[-1]:
        left = control._v[-1]
    else:
        control.t, control.v = np.array(control._t), np.array(control._v)
        left = float(control.at(np.array([start]), left=True)[0])
        k = bisect.bisect_left(control._t, start)
        del control._t[k:], control._v[k:]
    control._t += [start] + [p[0] for p in points]
    control._v += [left] + [p[1] for p in points]


@settings(max_examples=200, deadline=None)
@given(st.lists(curve, min_size=1, max_size=12), unit)
def test_overlapping_curves_give_the_points_of_the_whole_array_method(curves, default) -> None:
    ours, reference = _Control(default), _Control(default)
    for start, offsets in sorted(curves, key=lambda c: c[0]):
        points = sorted((start + dt, v) for dt, v in offsets)
        ours.set_from(start, points)
        _set_from_whole_arrays(reference, start, points)
    assert ours._t == reference._t
    assert ours._v == reference._v  # the same bits
