"""A vibration design holds its breakpoints as float64 arrays (issue 19: `convert` of hours of
sound) and still reads as the tuple of (t, v) pairs it stands for."""

from __future__ import annotations

import pickle
import tracemalloc

import numpy as np
import pytest

from timeline import edits
from timeline.edits.vibration import design_of, place_design
from timeline.errors import EditError
from timeline.signal.vibration_design import Breakpoints, Emphasis, VibrationDesign


def _ramp(n: int) -> np.ndarray:
    t = np.linspace(0.0, 10.0, n)
    return np.column_stack([t, 0.5 + 0.5 * np.sin(t)])


def test_breakpoints_read_as_tuples_of_python_floats():
    pairs = _ramp(5_000)  # more than one chunk of iteration
    design = VibrationDesign(pairs, ((0.0, 0.25), (10.0, 0.75)), (), 10.0)
    as_tuples = tuple(zip(pairs[:, 0].tolist(), pairs[:, 1].tolist(), strict=True))
    assert design.amplitude == as_tuples and as_tuples == design.amplitude
    assert tuple(design.amplitude) == as_tuples
    assert design.amplitude[-1] == as_tuples[-1] and type(design.amplitude[3][0]) is float
    assert design.amplitude[10:12] == as_tuples[10:12]
    assert design.frequency + ((10.0, 1.0),) == ((0.0, 0.25), (10.0, 0.75), (10.0, 1.0))
    assert np.array_equal(np.asarray(design.amplitude), pairs)
    assert design == VibrationDesign(as_tuples, design.frequency, (), 10.0)
    assert hash(design) == hash(VibrationDesign(as_tuples, design.frequency, (), 10.0))
    assert pickle.loads(pickle.dumps(design)) == design
    with pytest.raises(ValueError):
        design.amplitude.times[0] = 1.0
    with pytest.raises(EditError, match="breakpoint 2 goes back in time"):
        VibrationDesign(Breakpoints(np.array([1.0, 0.5]), np.array([0.1, 0.2])), (), (), 2.0)


def test_envelopes_read_from_the_arrays():
    design = VibrationDesign(((0.5, 0.2), (1.5, 0.6)), ((0.0, 0.0), (2.0, 1.0)), (), 2.0)
    u = np.array([0.0, 0.5, 1.0, 1.5, 1.75, 2.0])
    assert design.amplitude_at(u).tolist() == [0.0, 0.2, 0.4, 0.6, 0.0, 0.0]
    assert design.frequency_at(u).tolist() == [0.0, 0.25, 0.5, 0.75, 0.875, 1.0]
    later = design.shifted(1.0)
    assert later.amplitude == ((1.5, 0.2), (2.5, 0.6)) and later.duration == 3.0


def test_placing_and_reading_back_a_long_design_makes_no_object_per_breakpoint():
    n = 200_000
    pairs = _ramp(n)
    design = VibrationDesign(pairs, pairs * [1.0, 0.5], (Emphasis(5.0, 0.9, 0.3),), 10.0)
    arrays = 4 * n * 8  # both envelopes' times and values
    tracemalloc.start()
    try:
        project = place_design(edits.new_project(), design)
        back = design_of(project)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert back.amplitude == design.amplitude and back.frequency == design.frequency
    # tuples of two floats would take about 100 bytes a breakpoint (20 MB a copy here)
    assert peak < 3 * arrays
