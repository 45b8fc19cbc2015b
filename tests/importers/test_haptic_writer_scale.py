"""The .haptic writer puts many emphasis on the envelope in one walk, with the same bytes as the
per-emphasis insertion it replaced (kept here as the reference)."""

from __future__ import annotations

import json
from typing import Any

import numpy as np
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

from importers.lofelt import design_document
from timeline.edits.vibration import Emphasis, VibrationDesign

unit = st.floats(0.0, 1.0).map(lambda v: round(v, 4))
time = st.floats(0.0, 3.0).map(lambda t: round(t, 3))


def _attach_one_at_a_time(amplitude: list[dict[str, Any]], e: Emphasis, start: float) -> None:
    """The writer before it scaled: a search and an insert per emphasis (quadratic)."""
    times = [b["time"] for b in amplitude]
    lo = int(np.searchsorted(times, e.time, side="left"))
    hi = int(np.searchsorted(times, e.time, side="right"))
    free = [k for k in range(lo, hi) if "emphasis" not in amplitude[k]]
    if free:
        bp = amplitude[free[0]]
    else:
        if e.time > times[-1] or e.time < start:  # silent off the envelope (issue 23)
            level = 0.0
        elif hi > lo:
            level = amplitude[hi - 1]["amplitude"]
        else:
            level = float(np.interp(e.time, times, [b["amplitude"] for b in amplitude]))
        bp = {"time": e.time, "amplitude": level}
        amplitude.insert(hi, bp)
    bp["emphasis"] = {"amplitude": max(e.amplitude, bp["amplitude"]), "frequency": e.frequency}


def _reference(design: VibrationDesign) -> list[dict[str, Any]]:
    amplitude = [{"time": t, "amplitude": v} for t, v in design.amplitude]
    if len(amplitude) < 2 or amplitude[-1]["time"] <= amplitude[0]["time"]:
        amplitude = [{"time": 0.0, "amplitude": 0.0}, {"time": design.duration, "amplitude": 0.0}]
    first = amplitude[0]
    for e in design.emphasis:
        _attach_one_at_a_time(amplitude, e, first["time"])
    k = next(j for j, b in enumerate(amplitude) if b is first)
    if k and first["amplitude"] > 0:  # added before the envelope: it steps up at its start
        amplitude.insert(k, {"time": first["time"], "amplitude": 0.0})
    return amplitude


@st.composite
def crowded_designs(draw) -> VibrationDesign:
    """Designs with many emphasis: on breakpoints (several at one), between them, before the
    first, past the last, and several at one time off the envelope."""
    times = sorted(draw(st.lists(time, min_size=0, max_size=15)))
    amplitude = tuple((t, draw(unit)) for t in times)
    on = st.sampled_from(times) if times else time
    accent_times = draw(st.lists(st.one_of(on, time), min_size=1, max_size=80))
    accent_times += draw(st.lists(st.sampled_from(accent_times), max_size=20))
    accents = tuple(Emphasis(t, draw(unit), draw(unit)) for t in accent_times)
    duration = max([*times, *accent_times, 0.001]) + draw(st.sampled_from([0.0, 0.5]))
    return VibrationDesign(amplitude, (), accents, duration)


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(crowded_designs())
@example(
    VibrationDesign(
        ((0.2, 0.5), (1.0, 0.9), (1.0, 0.1), (2.0, 0.3)),
        (),
        tuple(Emphasis(t, 0.2, 0.5) for t in (0.0, 0.1, 0.4, 0.7, 1.0, 1.0, 1.0, 1.5, 2.5, 2.5)),
        3.0,
    )
)
def test_the_one_walk_writer_gives_the_bytes_of_the_one_at_a_time_writer(design) -> None:
    written = design_document(design)["signals"]["continuous"]["envelopes"]["amplitude"]
    assert json.dumps(written, indent=2) == json.dumps(_reference(design), indent=2)
    assert sum("emphasis" in b for b in written) == len(design.emphasis)


def test_ten_thousand_emphasis_off_the_envelope_keep_its_shape() -> None:
    """Emphasis between breakpoints ride on added ones at the envelope's own level."""
    rng = np.random.default_rng(5)
    accents = tuple(Emphasis(t, 1.0, 0.5) for t in rng.uniform(0.0, 10.0, 10_000))
    design = VibrationDesign(((0.0, 0.0), (10.0, 1.0)), (), accents, 10.0)
    written = design_document(design)["signals"]["continuous"]["envelopes"]["amplitude"]
    assert len(written) == 10_002
    t = np.array([b["time"] for b in written])
    v = np.array([b["amplitude"] for b in written])
    assert np.all(np.diff(t) >= 0)
    np.testing.assert_allclose(v, t / 10.0, rtol=0, atol=1e-12)
