"""The whole-loop growth against a brute-force reference: one companion matrix per sample.

The check finds the growth once per run of equal (k, b, m), once per distinct (k, b, m), and only
where every layer is inside its own limit (issue 19: at 20,000 clips it found 4.3 million roots
the findings never read). The numbers it reports must be those of every sample judged alone.
"""

from __future__ import annotations

import numpy as np

from tests.limits.designs import KNOB
from timeline import edits, generator
from timeline.limits import servo
from timeline.limits.check import check
from timeline.limits.design import sample
from timeline.limits.device_checks import JOIN
from timeline.limits.findings import spans
from timeline.model import Project


def _reference(rows: np.ndarray, k: float, b: float, m: float) -> float:
    """The largest root magnitude of one sample's polynomial: its companion's eigenvalues."""
    poly = rows[0] + k * rows[1] + b * rows[2] + m * rows[3]
    if not np.isfinite(poly).all():
        return np.inf
    n = poly.size - 1
    comp = np.zeros((n, n))
    comp[0] = -poly[1:] / poly[0]
    comp[np.arange(1, n), np.arange(n - 1)] = 1.0
    return float(np.abs(np.linalg.eigvals(comp)).max())


def _growth(k: np.ndarray, b: np.ndarray, m: np.ndarray, where: np.ndarray) -> np.ndarray:
    """Per sample, the worst growth over the loads that make it unstable (NaN: none, or not
    asked), each sample alone."""
    dyn, period = KNOB.dynamics, KNOB.period
    assert dyn is not None
    spring = np.maximum(k, 0.0)
    loop = servo.whole_loop(dyn, period, k, b, m, servo.hand_loads())
    out = np.full(k.size, np.nan)
    for load in servo.hand_loads():
        rows = servo.characteristic(dyn, period, load)
        for i in np.flatnonzero(loop.unstable.get(load.name, np.zeros(k.size, bool)) & where):
            out[i] = np.fmax(out[i], _reference(rows, spring[i], b[i], m[i]))
    return out


def test_growth_per_run_and_per_distinct_mix_is_each_samples_own():
    """Held runs, the same mix in runs far apart, a sloped stiffness, one layer stepping while
    the others hold: bit for bit."""
    rng = np.random.default_rng(5)
    mixes = np.column_stack([rng.uniform(-0.5, 1.5, 6), rng.uniform(0.0, 0.2, 6),
                             rng.uniform(0.0, 1.5e-4, 6)])  # fmt: skip
    held = np.repeat(mixes[rng.integers(0, 6, 40)], 5, axis=0)  # runs of 5, mixes repeated
    sloped = np.column_stack([np.linspace(0.0, 1.5, 60), np.full(60, 0.12), np.full(60, 1e-4)])
    steps = np.repeat(np.linspace(0.05, 0.2, 10), 3)  # one layer steps, the others held
    b_steps = np.column_stack([np.full(30, 0.8), steps, np.full(30, 1.2e-4)])
    m_steps = np.column_stack([np.full(30, 0.8), np.full(30, 0.12), steps * 1e-3])
    k, b, m = np.vstack([held, sloped, b_steps, m_steps]).T.copy()
    where = np.ones(k.size, bool)
    where[::7] = False  # the check asks only where every layer is inside
    dyn = KNOB.dynamics
    assert dyn is not None
    loop = servo.whole_loop(dyn, KNOB.period, k, b, m, servo.hand_loads(), where=where)
    expected = _growth(k, b, m, where)
    assert np.isfinite(expected).sum() > 50 and np.isnan(expected).sum() > 20
    np.testing.assert_array_equal(loop.radius, expected)


def _mixed(k: float, b: float, m: float, seconds: float = 0.1, pieces: int = 4) -> Project:
    """A sine of stiffness (k varies each sample) over held steps of damping and mass."""
    p = edits.new_project("time")
    for kind, value in (("stiffness", k), ("damping", b), ("mass", m)):
        p, track = edits.add_track(p, kind, kind)
        p = edits.set_track(p, track, full_scale=abs(value))
        if kind == "stiffness":
            p, tile = edits.add_tile(p, generator("sine", seconds, "wave", frequency=14.0))
            p, _ = edits.add_clip(p, track, tile, 0.0)
            continue
        p, tile = edits.add_tile(p, generator("constant", seconds / pieces, "level", value=1.0))
        for i in range(pieces):
            gain = (1.0 if value > 0 else -1.0) * (0.6 + 0.4 * i / pieces)
            p, _ = edits.add_clip(p, track, tile, i * seconds / pieces, gain=gain)
    return p


def test_check_reports_the_worst_growth_of_each_span_as_each_sample_gives_it():
    """Unstable-loop findings: spans and worst growth from the per-sample reference."""
    dyn = KNOB.dynamics
    assert dyn is not None
    found = 0
    for mix in ((1.0, 0.15, 1.2e-4), (0.5, 1e-6, -9.5e-6), (1.9, 0.3, 1.7e-4)):
        project = _mixed(*mix)
        design = sample(project, KNOB.rate)
        k, b, m = (design.terms[t] for t in "kbm")
        inside = servo.layers_inside(dyn, KNOB.period, k, b, m)
        growth = _growth(k, b, m, inside)
        bad = np.isfinite(growth)
        expected = [
            (design.position(lo), design.position(hi + 1), float(np.nanmax(growth[lo : hi + 1])))
            for lo, hi in spans(bad, join=round(JOIN * design.rate))
        ]
        reported = [
            (f.start, f.stop, f.value)
            for f in check(project, KNOB).findings
            if f.kind == "unstable-loop"
        ]
        assert reported == expected
        found += len(reported)
    assert found >= 3
