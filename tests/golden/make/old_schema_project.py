"""Save the golden old-schema project with the code of an old commit (schema 1 or 2).

This runs against that commit's timeline package, whose layout differs from today's
(timeline.projectfile, timeline.vibration_tile): see tests/golden/README.md.

    cd /tmp/old-1 && PYTHONPATH=/tmp/old-1 python old_schema_project.py OUT.htl
"""

import importlib.util
import sys

import numpy as np

from timeline import edits, projectfile
from timeline.tiles import SampledTile, generator, spline

p = edits.new_project("time", templates=False, title="Old schema", description="golden file")
p, drive = edits.add_track(p, "drive", "Buzz")
p, spring = edits.add_track(p, "stiffness", "Spring")
p, damping = edits.add_track(p, "damping", "Damping")
p = edits.set_track(p, spring, gain=0.5)
p, sine = edits.add_tile(p, generator("sine", 0.5, "ten hertz", frequency=10.0))
p, slow = edits.add_tile(p, generator("sine", 0.4, "five hertz", frequency=5.0))
p, swell = edits.add_tile(p, spline([(0.0, 0.0), (0.1, 0.3), (0.4, 1.0)], 0.4, "pchip", "swell"))
p, ramp = edits.add_tile(p, SampledTile(np.linspace(-1.0, 1.0, 41), 200.0, "ramp", "ramp.wav"))
p, a = edits.add_clip(p, drive, sine, 0.1, gain=0.5)
p = edits.set_fade(p, a, "in", 0.05, "linear")
p = edits.set_fade(p, a, "out", 0.1, "s-curve")
p, b = edits.add_clip(p, spring, slow, 0.0, gain=0.8)
p = edits.stretch_clip(p, b, 2.0)  # 2.5 Hz over 0.8 s
p, c = edits.add_clip(p, damping, ramp, 0.05, gain=0.3)
p, d = edits.add_clip(p, damping, swell, 0.5, gain=0.6)
p = edits.set_fade(p, d, "out", 0.2, "exponential")
if importlib.util.find_spec("timeline.vibration_tile"):  # schema 2: vibration tiles
    from timeline.vibration_design import Emphasis, VibrationDesign
    from timeline.vibration_tile import VibrationTile

    amplitude, frequency = ((0.0, 0.2), (0.05, 1.0), (0.3, 0.0)), ((0.0, 0.5), (0.3, 0.8))
    design = VibrationDesign(amplitude, frequency, (Emphasis(0.1, 0.9, 0.4),), 0.3)
    p, buzz = edits.add_tile(p, VibrationTile(design, "buzz", "buzz.ahap", "linear"))
    p, e = edits.add_clip(p, drive, buzz, 0.7, gain=0.6)
p = edits.save_variant(p, "A")
p = edits.set_clip_gain(p, a, 0.9)
p = edits.save_variant(p, "B: stronger")
p = edits.switch_variant(p, "A")
projectfile.save(p, sys.argv[1])
print(sys.argv[1], projectfile.SCHEMA)
