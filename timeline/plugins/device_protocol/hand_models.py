"""Named hands: how a pinch or a full grasp couples to the knob, from published measurements.

A hand model is a rotational mass-spring-damper between the knob and the hand's target angle:
an inertia that moves with the knob, a grip stiffness and a grip damping. The published values
are linear (a mass in kg, N/m, N*s/m at the point of contact); a hand holding a knob of radius r
at its rim turns them into rotation about the knob's axis as J = m*r^2, K = k*r^2, B = b*r^2
(derived, not measured on a knob). docs/devices.md lists the sources with each number.
"""

from __future__ import annotations

from dataclasses import dataclass

DEFAULT_MODEL = "default"


@dataclass(frozen=True)
class HandModel:
    """A hand's coupling to the knob: inertia (kg*m^2), stiffness (N*m/rad), damping (N*m*s/rad)."""

    name: str
    inertia: float
    stiffness: float
    damping: float
    radius: float  # m: the knob radius at which the fingers hold it (0 = not derived)
    source: str  # where the numbers come from, in one sentence

    @classmethod
    def at_rim(
        cls, name: str, mass: float, stiffness: float, damping: float, radius: float, source: str
    ) -> HandModel:
        """Rotate a linear mass (kg), stiffness (N/m) and damping (N*s/m) held at `radius` (m)."""
        r2 = radius * radius
        return cls(name, mass * r2, stiffness * r2, damping * r2, radius, source)


# The simulator's generic grip (before named hands existed): a round, stiff hold, not a measurement.
DEFAULT = HandModel(
    DEFAULT_MODEL, 2e-5, 1.0, 5e-3, 0.0, "the simulator's generic grip, not from a measurement"
)

# Fu & Cavusoglu 2012, three-finger stylus grip, Tables II-III: grasp stiffness k1 380-770 N/m
# and grasp damping b1 0.8-1.8 N*s/m over subjects, axes and 1-3 N grip force; midpoints taken.
# Their model puts no mass on the fingers' side of k1 (the 0.2 kg behind it is the hand and arm,
# here the grip target), so the pinch adds no inertia to the knob. Held at a 15 mm radius.
PINCH = HandModel.at_rim(
    "pinch",
    mass=0.0,
    stiffness=575.0,
    damping=1.3,
    radius=0.015,
    source=(
        "Fu & Cavusoglu 2012, IEEE Trans. SMC-B, Human Arm-and-Hand Dynamics Model with"
        " Variability Analyses for a Stylus-based Haptic Interface, Tables II-III (finger grasp"
        " k1, b1; midpoints), at a 15 mm knob radius"
    ),
)

# van Beek, Bergmann Tiest, Mugge & Kappers 2015, whole hand on the HapticMaster's handle, one
# participant's mass-damper-spring fit (Fig. 3f): M = 0.554 kg, B = 6.45 N*s/m, K = 135 N/m.
# Held at a 20 mm radius (a 40 mm knob in the whole hand).
GRASP = HandModel.at_rim(
    "grasp",
    mass=0.554,
    stiffness=135.0,
    damping=6.45,
    radius=0.020,
    source=(
        "van Beek, Bergmann Tiest, Mugge & Kappers 2015, Sci. Rep. 5:18004, Haptic perception of"
        " force magnitude and its relation to postural arm dynamics in 3D, Fig. 3f, at a 20 mm"
        " knob radius"
    ),
)

HAND_MODELS: dict[str, HandModel] = {m.name: m for m in (DEFAULT, PINCH, GRASP)}
