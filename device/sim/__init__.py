"""The simulated knob (`sim` device): physics, firmware model, hand model and stability limits."""

from device.sim.device import SimKnob
from device.sim.params import KnobParams
from device.sim.physics import KnobPhysics
from device.sim.stability import passive_stiffness, stability_flags, stable_stiffness

__all__ = [
    "KnobParams",
    "KnobPhysics",
    "SimKnob",
    "passive_stiffness",
    "stability_flags",
    "stable_stiffness",
]
