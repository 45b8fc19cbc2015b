"""How far the skin moves for one unit of drive at a frequency: the bridge from a design's
numbers to the detection threshold.

* A vibrotactile actuator shakes the hand with its peak acceleration (g at full scale) times its
  frequency response; displacement = acceleration / (2*pi*f)^2.
* A knob turns against its rotor and the hand: angle = torque / |K_h - (J + J_h)*w^2 +
  j*w*(b + B_h)|, and the fingertip on its rim moves radius * angle. K_h, B_h and J_h are the
  given hand's (timeline.plugins.device_protocol.Hand: `check --hand`, the editor's transport;
  a pushing hand has no grip, only its inertia); the radius is its model's (pinch 15 mm, grasp 20
  mm) or KNOB_RADIUS, a typical control knob. A hand that lets go (`free`) feels nothing: None.
"""

from __future__ import annotations

import numpy as np

from timeline.plugins.device_protocol import Actuator, DeviceInfo, Hand
from timeline.plugins.device_protocol.hand_models import HAND_MODELS

KNOB_RADIUS = 0.015  # m: where the fingertips touch a 30 mm knob
G = 9.81  # m/s^2


def displacement_per_unit(
    info: DeviceInfo, actuator: Actuator | None, frequency: np.ndarray, hand: Hand | None = None
) -> np.ndarray | None:
    """Peak skin displacement (m) per unit of drive (in the device's output unit); None if unknown
    or nothing touches the knob.

    An actuator's full scale is the device's maximum output; a knob's hand defaults to `hold`.
    """
    # an infinite frequency (an ADSR released over 1e308 s) moves the skin as little as 1e15 Hz
    f = np.clip(np.asarray(frequency, dtype=np.float64), 1.0, 1e15)
    w = 2.0 * np.pi * f
    if actuator is not None:
        return actuator.peak_acceleration * G * actuator.gain(f) / (w * w) / info.max_output
    if info.kind != "kinesthetic" or info.dynamics is None:
        return None
    hand = hand or Hand("hold")
    if not hand.touches:
        return None
    dyn = info.dynamics
    grip_k, grip_b = (hand.grip_stiffness, hand.grip_damping) if hand.grips else (0.0, 0.0)
    z = grip_k - (dyn.inertia + hand.inertia) * w * w + 1j * w * (dyn.damping + grip_b)
    return (HAND_MODELS[hand.model].radius or KNOB_RADIUS) / np.abs(z)
