"""A new damping lane's full scale is what the default knob renders, and a full-scale clip is felt.

The damping kind's full scale (0.2 N*m*s/rad) sits at the default sim's damping limit, so one
clip of 1.0 on a new project asks for the strongest stable brake and the knob gives it: turned at
20 deg/s it brakes with tens of mNm, far above a force JND (7 %, Jones 1989, docs/perception.md)
of the fan knob's 29 mNm detents; the old full scale (1e-4) asked 1e-4 x 0.35 rad/s = 0.035 mNm.
"""

from __future__ import annotations

import numpy as np
import pytest

from timeline import edits, generator, render
from timeline.limits.rendered import knob
from timeline.limits.servo import damping_limit
from timeline.limits.thresholds import FORCE_JND
from timeline.plugins.device_protocol import Hand, open_device

DETENTS = 0.029  # N*m: the fan knob's detent peaks, 0.8 x 0.2 x 180 mNm


def test_a_full_scale_damping_clip_renders_the_limit_and_is_felt() -> None:
    p = edits.new_project("time", templates=False)
    p, track = edits.add_track(p, "damping", "Damping")
    p, tile = edits.add_tile(p, generator("constant", 0.5, "level", value=1.0))
    p, _ = edits.add_clip(p, track, tile, 0.0)
    assert np.all(render(p)["damping"] == 0.2)
    info = open_device("sim").info
    assert damping_limit(info.dynamics, 1.0 / info.rate) == pytest.approx(0.20021, abs=1e-5)
    trace = knob(p, info, Hand("turn", 20.0))
    late = trace.time > 0.4  # the last 0.1 s, the knob lagging the hand
    brake, designed = np.abs(trace.rendered[late]), np.abs(trace.designed[late])
    assert brake.min() > FORCE_JND * DETENTS  # a JND of the detents: 2 mNm
    # on average what 0.2 N*m*s/rad asks at the knob's speed (up to the hand's 70 mNm): unclamped
    assert brake.mean() == pytest.approx(designed.mean(), rel=0.01)
    assert 0.05 < designed.mean() < 0.2 * np.radians(20.0)
