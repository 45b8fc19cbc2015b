"""The passivity limit: computed, flagged exactly at the boundary, and felt as energy growth."""

from __future__ import annotations

import numpy as np
import pytest

from device.sim import KnobParams, KnobPhysics, passive_stiffness, stability_flags, stable_stiffness
from timeline.plugins.device_protocol import CoefficientBlock, Hand

TEXTBOOK = dict(quantum=0.0, coulomb=0.0, velocity_cutoff=0.0)


def test_limits_match_the_reference_numbers() -> None:
    assert passive_stiffness(1e-4, 0.0, 1e-4) == pytest.approx(2.0)
    assert passive_stiffness(1e-3, 5e-4, 1e-4) == pytest.approx(10.0)
    assert passive_stiffness(1e-3, -5e-4, 1e-4) == pytest.approx(10.0)
    assert stable_stiffness(1e-3, 5e-4, 1e-4) == pytest.approx(30.0)


@pytest.mark.parametrize("viscous", [1e-4, 1e-3])
@pytest.mark.parametrize("virtual_damping", [0.0, 2e-5, -3e-5])
@pytest.mark.parametrize("rate", [1_000.0, 10_000.0, 40_000.0])
def test_flag_fires_exactly_above_the_boundary(
    viscous: float, virtual_damping: float, rate: float
) -> None:
    p = KnobParams(rate=rate, viscous=viscous)
    limit = passive_stiffness(viscous, virtual_damping, p.period)
    k = np.array([np.nextafter(limit, 0.0), limit, np.nextafter(limit, np.inf), 1.01 * limit])
    flags = stability_flags(
        np.arange(4) / rate, k, np.full(4, virtual_damping), None, p.dynamics, p.period
    )
    passivity = [f for f in flags if f.kind == "passivity"]
    assert len(passivity) == 1
    np.testing.assert_array_equal(passivity[0].times, np.arange(2, 4) / rate)
    assert passivity[0].margins[0] > 0
    assert passivity[0].margins[1] == pytest.approx(0.01 * limit)


def _free_ring(k: float, seconds: float = 3.0) -> tuple[np.ndarray, np.ndarray]:
    """Kick a free textbook knob on a spring k and return its energy and angle records."""
    p = KnobParams(**TEXTBOOK)
    knob = KnobPhysics(p)
    knob.start(Hand("free"))
    n = int(seconds * p.rate)
    d = np.zeros(n)
    d[:5] = 0.01  # a short kick
    tel = knob.run_block(CoefficientBlock(d, np.full(n, k), np.zeros(n)))
    return tel.energy, tel.angle


@pytest.mark.parametrize("fraction", [0.97, 1.03])  # 3 % either side of K_pass
def test_energy_stays_bounded_below_the_limit_and_grows_above(fraction: float) -> None:
    limit = passive_stiffness(KnobParams().viscous, 0.0, KnobParams().period)
    energy, angle = _free_ring(fraction * limit)
    quarter = len(angle) // 4
    early, late = np.abs(angle[:quarter]).max(), np.abs(angle[-quarter:]).max()
    assert np.isfinite(energy).all() and np.isfinite(angle).all()
    if fraction < 1:
        assert late < 0.8 * early  # the ring decays
        assert energy[-quarter:].max() <= energy[:quarter].max()  # energy stays bounded
    else:
        assert late > 1.2 * early  # the ring grows
        assert energy[-quarter:].max() > 1.4 * energy[:quarter].max()  # the device injects energy


def test_far_above_the_limit_the_knob_still_simulates_without_nan() -> None:
    knob = KnobPhysics()
    knob.start(Hand("free"))
    n = 20_000
    d = np.zeros(n)
    d[:10] = 0.05
    tel = knob.run_block(CoefficientBlock(d, np.full(n, 50.0), np.zeros(n)))
    assert np.isfinite(tel.angle).all() and np.isfinite(tel.torque).all()
    assert tel.flag("passivity").count == n
    assert tel.time_saturated > 0.5 and tel.energy_injected > 0


def test_negative_damping_and_cancelled_inertia_are_flagged_and_finite() -> None:
    p = KnobParams()
    knob = KnobPhysics(p)
    knob.start(Hand("hold"))
    n = 5000
    m = np.full(n, -0.5 * p.inertia)
    m[2000:] = -p.inertia  # J + m = 0 from 0.2 s
    b = np.zeros(n)
    b[1000:1100] = -1e-4
    d = np.zeros(n)
    d[:10] = 0.01
    tel = knob.run_block(CoefficientBlock(d, np.zeros(n), b, m))
    assert tel.flag("negative-damping").first_time == pytest.approx(0.1)
    assert tel.flag("negative-damping").count == 100
    cancel = tel.flag("mass-cancels-inertia")
    assert cancel.first_time == pytest.approx(0.2) and cancel.count == 3000
    assert np.isfinite(tel.torque).all() and np.isfinite(tel.angle).all()


def test_mass_boundary_is_exactly_minus_the_rotor_inertia() -> None:
    p = KnobParams()
    m = np.array([np.nextafter(-p.inertia, 0.0), -p.inertia, np.nextafter(-p.inertia, -1.0)])
    flags = stability_flags(np.arange(3.0), np.zeros(3), np.zeros(3), m, p.dynamics, p.period)
    assert [f.kind for f in flags] == ["mass-cancels-inertia"]
    np.testing.assert_array_equal(flags[0].times, [1.0, 2.0])
