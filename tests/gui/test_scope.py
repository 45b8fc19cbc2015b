"""The transport scope cuts its traces to one (min, max) per pixel column, exactly."""

from __future__ import annotations

import numpy as np
import pytest

from timeline.gui.scope import Scope, _Polyline, column_extremes, trace_points


def reference(values: np.ndarray, width: int) -> tuple[np.ndarray, np.ndarray]:
    """Plain numpy: value j is drawn in pixel column j * width // n."""
    column = np.arange(values.size) * width // values.size
    lo = np.array([values[column == c].min() for c in range(width)])
    hi = np.array([values[column == c].max() for c in range(width)])
    return lo, hi


@pytest.mark.parametrize(("n", "width"), [(4000, 373), (4000, 600), (601, 600), (1000, 1000)])
def test_each_column_keeps_its_min_and_max(n, width):
    values = np.random.default_rng(n + width).standard_normal(n)
    lo, hi = column_extremes(values, width)
    want_lo, want_hi = reference(values, width)
    np.testing.assert_array_equal(lo, want_lo)
    np.testing.assert_array_equal(hi, want_hi)


def test_the_polyline_visits_every_columns_min_and_max():
    values = np.random.default_rng(1).standard_normal(4000)
    points = trace_points(values, 250)
    lo, hi = reference(values, 250)
    assert points.shape == (500, 2)
    np.testing.assert_array_equal(points[:, 0], np.repeat(np.arange(250) + 0.5, 2))
    pairs = points[:, 1].reshape(250, 2)
    np.testing.assert_array_equal(pairs.min(axis=1), lo)
    np.testing.assert_array_equal(pairs.max(axis=1), hi)


def test_fewer_values_than_pixels_are_drawn_as_they_are():
    values = np.array([0.0, 2.0, -1.0])
    np.testing.assert_array_equal(trace_points(values, 100), [[0, 0], [50, 2], [100, -1]])


def test_the_polygon_is_filled_through_its_own_memory(qapp):
    line = _Polyline()
    points = np.array([[0.5, 1.0], [1.5, -2.0], [2.5, 3.25]])
    polygon = line.filled(points)
    assert [(polygon.at(i).x(), polygon.at(i).y()) for i in range(3)] == [
        (0.5, 1.0), (1.5, -2.0), (2.5, 3.25)
    ]  # fmt: skip
    again = line.filled(points[::-1].copy())
    assert again is polygon and (polygon.at(0).x(), polygon.at(0).y()) == (2.5, 3.25)


def test_the_scope_repaints_only_when_telemetry_arrived(qtbot):
    scope = Scope()
    qtbot.addWidget(scope)
    scope.add(np.zeros(0), np.zeros(0))
    assert scope.tau.size == 0
    scope.add(np.full(100, np.pi), np.full(100, 0.002))
    np.testing.assert_allclose(scope.theta, np.full(10, 180.0))
    np.testing.assert_allclose(scope.tau, np.full(10, 2.0))
    scope.resize(300, 120)
    assert not scope.grab().isNull()
