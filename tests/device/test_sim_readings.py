"""The compiled telemetry pass equals the numpy/scipy formulas it replaced, bit for bit."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays
from scipy.signal import lfilter

from device.sim.readings import blow_up_index, readings

ANGLES = arrays(np.float64, st.integers(1, 60), elements=st.floats(-1e3, 1e3))


def reference(thetas, end, taus, frictions, losses, quantum, anchor, rate, av, prev_meas, vel,
              energy0):  # fmt: skip
    """What physics.py computed with numpy and lfilter before the compiled pass (the viscous
    loss per period now comes from the servo loop)."""
    path = np.append(thetas, end)
    meas = (np.floor(thetas * (1.0 / quantum) + 0.5) * quantum if quantum else thetas) - anchor
    raw = np.diff(meas, prepend=prev_meas) * rate
    velocity = lfilter([av], [1.0, av - 1.0], raw, zi=[(1.0 - av) * vel])[0]
    step = np.diff(path)
    dissipated = losses - frictions * step
    return meas, velocity, energy0 + np.cumsum(taus * step - dissipated)


@settings(max_examples=200, deadline=None)
@given(
    ANGLES,
    st.floats(-1e3, 1e3),
    st.sampled_from([0.0, np.radians(0.001), 0.01]),
    st.sampled_from([1.0, 0.7121, 0.0609]),
    st.floats(-1.0, 1.0),
    st.floats(-50.0, 50.0),
    st.floats(-1.0, 1.0),
)
def test_readings_equal_the_numpy_formulas(thetas, end, quantum, av, prev, vel, energy0) -> None:
    rng = np.random.default_rng(thetas.size)
    taus, frictions = rng.normal(0, 0.1, thetas.size), rng.normal(0, 1e-3, thetas.size)
    losses = rng.uniform(0, 1e-6, thetas.size)
    args = (0.25, 10_000.0)
    got = readings(thetas, end, taus, frictions, losses, (quantum, *args), (av, prev, vel),
                   energy0)  # fmt: skip
    want = reference(thetas, end, taus, frictions, losses, quantum, *args, av, prev, vel, energy0)
    for a, b in zip(got, want, strict=True):
        assert a.tobytes() == b.tobytes()


def test_blow_up_is_the_first_period_ending_non_finite_or_too_fast() -> None:
    thetas = np.array([0.0, 1e-4, 2e-4, 200.0, np.nan])
    assert blow_up_index(thetas, 0.0, 10_000.0, 1e6) == 2  # 200 rad in 0.1 ms: 2e6 rad/s
    assert blow_up_index(thetas[:3], 3e-4, 10_000.0, 1e6) == 3  # none
    assert blow_up_index(thetas[:3], np.inf, 10_000.0, 1e6) == 2  # ends at infinity
    assert blow_up_index(thetas[3:], 0.0, 10_000.0, 1e6) == 0  # NaN after the first period
    assert blow_up_index(thetas[:3], 3e-4, 10_000.0, 0.5) == 0  # 1 rad/s from the start
