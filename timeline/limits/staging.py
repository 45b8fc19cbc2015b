"""The level a converted design should take on a device: its limit, and what a hand feels.

As fractions of the drive's full scale, for timeline.analysis.staging: the device's largest
output, and the least peak a hand holding it feels clearly, SENSATION_DB above Verrillo's
detection threshold (thresholds.py) at the least sensitive frequency of the design carrier's
range (skin.py turns a drive into skin displacement). 20 dB is within the 20-35 dB sensation
levels at which Israr, Tan & Reed (2006) measured amplitude discrimination: clearly felt.
"""

from __future__ import annotations

import numpy as np

from timeline.analysis.staging import Staging
from timeline.edits.vibration import DRIVE
from timeline.limits.skin import displacement_per_unit
from timeline.limits.thresholds import detection_threshold
from timeline.plugins.device_protocol import Actuator, DeviceInfo
from timeline.plugins.track_kinds import track_kind
from timeline.signal.vibration_design import F_MAX, F_MIN

SENSATION_DB = 20.0  # dB above the detection threshold where `--gain auto` puts a quiet design


def staging_for(
    info: DeviceInfo, actuator: Actuator | None = None, gain_db: float | None = None
) -> Staging:
    """The staging of a design for a device (and the actuator it drives, if vibrotactile)."""
    chosen = actuator or info.actuator
    # a drive of 1 is the drive kind's full scale on a knob, the device's full scale otherwise
    unit = track_kind(DRIVE).full_scale if info.kind == "kinesthetic" else 1.0
    carrier = np.linspace(F_MIN, F_MAX, 16)
    per_unit = displacement_per_unit(info, chosen, carrier)
    felt = 0.0
    if per_unit is not None:
        needed = detection_threshold(carrier) / (per_unit * unit)
        felt = float(needed.max()) * 10.0 ** (SENSATION_DB / 20.0)
    return Staging(limit=info.max_output / unit, felt=felt, gain_db=gain_db, target=info.name)
