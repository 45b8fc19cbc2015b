"""The passivity limit over grids of rate, device damping and virtual damping (textbook knob).

tests/device/test_sim_stability.py checks the flag boundary to the last bit and one energy case
(10 kHz, B = 0). Here every grid point renders a kicked free knob for a long hold of constant
coefficients 3 % below and 3 % above the limit: the passivity warning fires exactly when k is
above K_pass = 2*(b_dev - |B|)/T, and the energy stays bounded below the limit the free knob
obeys (K_stab = 2*(b_dev + B)/T, equal to K_pass when B = 0) and grows above it.
With negative virtual damping at the coarsest rate the ring's boundary moves away from K_stab
(w*h ~ 0.4 there, beyond the small-step derivation), so B < 0 is checked for the warning only.
"""

from __future__ import annotations

import numpy as np
import pytest

from device.sim import KnobParams, KnobPhysics, passive_stiffness, stable_stiffness
from timeline.plugins.device_protocol import CoefficientBlock, Hand, Telemetry

TEXTBOOK = dict(quantum=0.0, coulomb=0.0, velocity_cutoff=0.0)
HOLD = 2.0  # s of constant coefficients after the kick
RATES = [1_000.0, 10_000.0, 40_000.0]
DEVICE_DAMPING = [1e-4, 1e-3]


def hold(p: KnobParams, k: float, b: float) -> Telemetry:
    """Kick a free knob and hold a spring k and virtual damping b constant."""
    knob = KnobPhysics(p)
    knob.start(Hand("free"))
    n = int(HOLD * p.rate)
    d = np.zeros(n)
    d[: max(1, int(5e-4 * p.rate))] = 0.005  # a 0.5 ms kick
    return knob.run_block(CoefficientBlock(d, np.full(n, k), np.full(n, b)))


def grows(tel: Telemetry) -> bool:
    """True when the ring's amplitude and the injected energy are larger late than early."""
    quarter = len(tel.angle) // 4
    early, late = np.abs(tel.angle[:quarter]).max(), np.abs(tel.angle[-quarter:]).max()
    return bool(late > early and tel.energy[-quarter:].max() > tel.energy[:quarter].max())


def bounded(tel: Telemetry) -> bool:
    """True when the ring decays and the energy never exceeds its early peak."""
    quarter = len(tel.angle) // 4
    early, late = np.abs(tel.angle[:quarter]).max(), np.abs(tel.angle[-quarter:]).max()
    return bool(late < early and tel.energy.max() <= tel.energy[:quarter].max())


@pytest.mark.parametrize("rate", RATES)
@pytest.mark.parametrize("viscous", DEVICE_DAMPING)
@pytest.mark.parametrize("fraction", [0.97, 1.03])
def test_energy_and_warning_switch_at_the_limit(
    rate: float, viscous: float, fraction: float
) -> None:
    p = KnobParams(rate=rate, viscous=viscous, **TEXTBOOK)
    limit = passive_stiffness(viscous, 0.0, p.period)
    assert limit == stable_stiffness(viscous, 0.0, p.period)
    tel = hold(p, fraction * limit, 0.0)
    assert np.isfinite(tel.angle).all() and np.isfinite(tel.energy).all()
    flag = tel.flag("passivity")
    if fraction < 1:
        assert flag is None
        assert bounded(tel)
    else:
        assert flag is not None and flag.count == len(tel)
        assert grows(tel)


@pytest.mark.parametrize("rate", RATES)
@pytest.mark.parametrize("viscous", DEVICE_DAMPING)
def test_positive_virtual_damping_warns_before_the_free_knob_grows(
    rate: float, viscous: float
) -> None:
    """With B > 0, K_pass < K_stab: between them the warning fires (a hand could destabilise
    it) while the free knob still rings down; above K_stab its energy grows."""
    p = KnobParams(rate=rate, viscous=viscous, **TEXTBOOK)
    b = 0.3 * viscous
    k_pass, k_stab = passive_stiffness(viscous, b, p.period), stable_stiffness(viscous, b, p.period)
    between = hold(p, 0.97 * k_stab, b)
    assert 0.97 * k_stab > k_pass
    assert between.flag("passivity").count == len(between)
    assert bounded(between)
    assert grows(hold(p, 1.03 * k_stab, b))


@pytest.mark.parametrize("rate", RATES)
@pytest.mark.parametrize("share", [-0.3, 0.3])
@pytest.mark.parametrize("fraction", [0.97, 1.03])
def test_warning_with_virtual_damping_follows_k_pass(
    rate: float, share: float, fraction: float
) -> None:
    p = KnobParams(rate=rate, **TEXTBOOK)
    b = share * p.viscous
    limit = passive_stiffness(p.viscous, b, p.period)
    tel = hold(p, fraction * limit, b)
    assert np.isfinite(tel.angle).all() and np.isfinite(tel.energy).all()
    flag = tel.flag("passivity")
    assert (flag is not None and flag.count == len(tel)) if fraction > 1 else flag is None
