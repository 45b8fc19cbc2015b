"""Build the example projects that ship in projects/ (run again when the schema changes).

python projects/build_examples.py            # writes projects/*.htl
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

from timeline import edits, generator, save, spline
from timeline.edits import markers
from timeline.model import Project

HERE = Path(__file__).resolve().parent
deg = math.radians
# The walls' torque gain and damping: 0.8 x 180 mNm over 20 degrees is 0.413 N*m/rad, with 3e-5
# N*m*s/rad of damping, below the 0.467 N*m/rad a knob with a one-period computation delay renders
# passively at 10 kHz ((b_dev - B) / (1.5 T), docs/perception.md) and twice the detents' steepest
# slope (0.216 N*m/rad).
WALL = 0.8
WALL_DAMPING = 0.3
# The damping and mass lanes' own full scales: a knob's light damping (tens of uN*m*s/rad) and
# mass (a few g*cm^2) are small beside what the device renders (the kinds' full scales, 0.2
# N*m*s/rad and 2.8e-5 kg*m^2), so these lanes span 0.1 mNm*s/rad and 100 g*cm^2 and their
# clips' gains read as fractions of that.
LIGHT_DAMPING = 1e-4  # N*m*s/rad
LIGHT_MASS = 1e-5  # kg*m^2


def fan_knob() -> Project:
    """The paper's fan knob (position axis): walls beyond Off and Hi, four detents between.

    Detent rest angles: Off 50, Lo 110, Med 170, Hi 230 degrees; walls below 20 and above 260.
    Light damping in range, stronger beyond the ends, constant mass. The walls and the damping
    stay inside the delayed passivity bound (see WALL), so `check` is quiet on a USB knob too.
    """
    p = edits.new_project("position", title="Fan knob", description=fan_knob.__doc__.split("\n")[0])
    p, torque = edits.add_track(p, "torque", "Walls and detents")
    p, damping = edits.add_track(p, "damping", "Damping")
    p, mass = edits.add_track(p, "mass", "Mass")
    p = edits.set_track(p, damping, full_scale=LIGHT_DAMPING)
    p = edits.set_track(p, mass, full_scale=LIGHT_MASS)
    p, wall = edits.add_tile(p, generator("wall", deg(20), "wall", edge=0.0, width=1.0), "Scratch")
    p, detents = edits.add_tile(
        p, generator("detents", deg(240), "four detents", count=4, phase=-0.5), "Scratch"
    )
    p, level = edits.add_tile(p, generator("constant", deg(20), "level", value=1.0), "Scratch")
    # Lower wall: reversed and inverted so it pushes towards higher angles below 20 degrees.
    p, low = edits.add_clip(p, torque, wall, 0.0, gain=WALL)
    p = edits.reverse_clip(p, low)
    p = edits.invert_clip(p, low)
    p, _ = edits.add_clip(p, torque, detents, deg(20), gain=0.2)
    p, _ = edits.add_clip(p, torque, wall, deg(260), gain=WALL)
    p, _ = edits.add_clip(p, damping, level, 0.0, gain=WALL_DAMPING)
    p, mid = edits.add_clip(p, damping, level, deg(20), gain=0.2)
    p = edits.stretch_clip(p, mid, 12.0, "repeat")
    p, _ = edits.add_clip(p, damping, level, deg(260), gain=WALL_DAMPING)
    p, whole = edits.add_clip(p, mass, level, 0.0, gain=0.2)
    p = edits.stretch_clip(p, whole, 14.0, "repeat")
    for name, at in (("Off", 50), ("Lo", 110), ("Med", 170), ("Hi", 230)):
        p, _ = markers.add_marker(p, deg(at), name)  # the fan's settings, on the ruler
    return p


def notification_buzz() -> Project:
    """Two buzzes for a vibrotactile actuator: a modulated 175 Hz burst, then a short tap."""
    p = edits.new_project("time", title="Notification buzz")
    p, drive = edits.add_track(p, "drive", "Buzz")
    p, burst = edits.add_tile(
        p, generator("am", 0.3, "burst", carrier=175.0, modulation=8.0, depth=0.5), "Scratch"
    )
    p, tap = edits.add_tile(p, generator("sine", 0.1, "tap", frequency=175.0), "Scratch")
    p, first = edits.add_clip(p, drive, burst, 0.0, gain=0.8)
    p = edits.set_fade(p, first, "in", 0.02, "equal-power")
    p = edits.set_fade(p, first, "out", 0.08, "exponential")
    p, second = edits.add_clip(p, drive, tap, 0.4, gain=0.6)
    p = edits.set_fade(p, second, "out", 0.05, "s-curve")
    p = edits.save_variant(p, "A")
    p = edits.set_clip_gain(p, second, 0.9)
    p = edits.save_variant(p, "B: stronger tap")
    return edits.switch_variant(p, "A")


def rising_resistance() -> Project:
    """A knob that stiffens over two seconds while its damping swells (time axis)."""
    p = edits.new_project("time", title="Rising resistance")
    p, stiffness = edits.add_track(p, "stiffness", "Spring")
    p, damping = edits.add_track(p, "damping", "Damping")
    p = edits.set_track(p, damping, full_scale=LIGHT_DAMPING)
    p, ramp = edits.add_tile(p, generator("ramp", 2.0, "ramp up", start=0.0, end=1.0), "Scratch")
    p, swell = edits.add_tile(
        p, spline([(0.0, 0.0), (1.0, 0.3), (2.0, 1.0)], 2.0, "pchip", "swell"), "Scratch"
    )
    p, _ = edits.add_clip(p, stiffness, ramp, 0.0, gain=0.4)  # 0.4 N*m/rad at 2 s
    p, _ = edits.add_clip(p, damping, swell, 0.0, gain=0.3)  # 3e-5 N*m*s/rad at 2 s
    return p


EXAMPLES = {
    "fan_knob.htl": fan_knob,
    "notification_buzz.htl": notification_buzz,
    "rising_resistance.htl": rising_resistance,
}


def main(folder: Path = HERE) -> None:
    for name, build in EXAMPLES.items():
        save(build(), folder / name)
        print(f"wrote {folder / name}")


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else HERE)
