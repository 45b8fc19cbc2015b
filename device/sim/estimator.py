"""How the simulated firmware's velocity and acceleration estimates follow the true motion.

Velocity: backward difference of the encoder reading, first-order low-pass (gain av per period).
Acceleration: backward difference of that velocity estimate, first-order low-pass (gain aa).
With an ideal sensor both are linear filters of the angle; at a frequency f their ratio to the
true derivative is H(z) / (j*w)^k with z = exp(j*w*T), which is what `velocity_response` and
`acceleration_response` return (complex: gain and phase).
"""

from __future__ import annotations

import numpy as np

from device.sim.params import KnobParams


def _stage(params: KnobParams, cutoff: float, z: np.ndarray) -> np.ndarray:
    a = params.smoothing(cutoff)
    return a * (1.0 - 1.0 / z) * params.rate / (1.0 - (1.0 - a) / z)


def velocity_response(params: KnobParams, frequency) -> np.ndarray:  # noqa: ANN001
    """Estimated over true velocity at frequencies (Hz), ideal sensor, steady state."""
    w = 2.0 * np.pi * np.asarray(frequency, dtype=np.float64)
    z = np.exp(1j * w * params.period)
    return _stage(params, params.velocity_cutoff, z) / (1j * w)


def acceleration_response(params: KnobParams, frequency) -> np.ndarray:  # noqa: ANN001
    """Estimated over true acceleration at frequencies (Hz), ideal sensor, steady state."""
    w = 2.0 * np.pi * np.asarray(frequency, dtype=np.float64)
    z = np.exp(1j * w * params.period)
    chain = _stage(params, params.velocity_cutoff, z) * _stage(
        params, params.acceleration_cutoff, z
    )
    return chain / (1j * w) ** 2


def acceleration_noise(params: KnobParams, sigma: float) -> float:
    """RMS acceleration estimate (rad/s^2) for white reading noise sigma: sigma times the RMS of
    the filter chain's gain over the band (Parseval, midpoint rule on 100,000 bins)."""
    w = (np.arange(100_000) + 0.5) * np.pi / 100_000
    z = np.exp(1j * w)
    chain = _stage(params, params.velocity_cutoff, z) * _stage(
        params, params.acceleration_cutoff, z
    )
    return float(sigma * np.sqrt(np.mean(np.abs(chain) ** 2)))
