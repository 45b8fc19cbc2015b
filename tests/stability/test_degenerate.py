"""Degenerate inputs give a correct result or one clear error: never NaN, never a hang.

tests/core/test_extremes.py covers stretch 1e-3/1e3 of a generator, rates 1 Hz..192 kHz of a
ramp and refused edits; tests/device/test_sim_stability.py covers J + m = 0 under a holding hand.
Here: zero-length clips and fades, sub-sample clips, extreme stretch of recordings in both
stretch modes and at every preset, a mass layer at and beyond -J with the knob let go, 1 Hz
renders of recordings and a 1 Hz knob.
"""

from __future__ import annotations

import numpy as np
import pytest

from device.sim import KnobParams, KnobPhysics
from timeline import Mixer, edits
from timeline.errors import EditError
from timeline.model import Clip
from timeline.plugins.device_protocol import CoefficientBlock, Hand
from timeline.signal.render_presets import PRESETS
from timeline.tiles import SampledTile, generator

FULL = 0.18  # N*m, the drive track's full scale


def one_clip(tile, start: float = 0.0):
    project = edits.new_project(templates=False)
    project, track = edits.add_track(project, "drive")
    project, tile_id = edits.add_tile(project, tile)
    project, clip = edits.add_clip(project, track, tile_id, start)
    return project, clip, tile_id


def recording(seconds: float = 1.0, rate: float = 48_000.0, high: float = 0.1) -> SampledTile:
    """50 Hz plus `high` x a 9 kHz tone, above the 10 kHz grid's Nyquist."""
    t = np.arange(int(seconds * rate)) / rate
    return SampledTile(np.sin(2 * np.pi * 50 * t) + high * np.sin(2 * np.pi * 9_000 * t), rate)


def test_zero_length_clips_are_refused_clearly() -> None:
    project, clip, tile_id = one_clip(generator("sine", 1.0))
    with pytest.raises(EditError, match="positive length"):
        Clip("z", tile_id, 0.0, 0.5, 0.5)
    with pytest.raises(EditError, match="trimmed to nothing"):
        edits.trim_clip(project, clip, start=0.3, end=0.3)


def test_zero_length_fades_render_as_no_fade() -> None:
    project, clip, _ = one_clip(generator("sine", 1.0, frequency=10))
    faded = edits.set_fade(edits.set_fade(project, clip, "in", 0.0), clip, "out", 0.0, "s-curve")
    np.testing.assert_array_equal(Mixer().render(faded)["drive"], Mixer().render(project)["drive"])


def test_fade_as_long_as_the_clip_is_finite_and_ends_at_zero() -> None:
    project, clip, _ = one_clip(generator("constant", 1.0, value=1.0))
    for shape in ("linear", "equal-power", "exponential", "s-curve"):
        p = edits.set_fade(edits.set_fade(project, clip, "in", 1.0, shape), clip, "out", 1.0, shape)
        out = Mixer().render(p, 0.0, 1.0)["drive"]
        assert np.isfinite(out).all() and out[0] == 0.0 and out.max() <= FULL


def test_a_clip_shorter_than_a_sample_renders_at_most_one_sample() -> None:
    tile = generator("constant", 1e-6, value=1.0)
    for start in (0.25, 0.25 + 0.5e-4, 0.25 + 0.99e-4):
        project, _, _ = one_clip(tile, start)
        out = Mixer().render(project, 0.0, 0.5)["drive"]
        assert np.isfinite(out).all() and np.count_nonzero(out) <= 1 and out.max() <= FULL


@pytest.mark.parametrize("quality", list(PRESETS))
@pytest.mark.parametrize("mode", ["squeeze", "repeat"])
@pytest.mark.parametrize("factor", [1e-3, 1e3])
def test_recordings_at_extreme_stretch_stay_finite(quality: str, mode: str, factor: float) -> None:
    project, clip, _ = one_clip(recording(0.5))
    project = edits.stretch_clip(project, clip, factor, mode)
    stop = min(project.duration, 3.0)
    out = np.asarray(Mixer().render(project, 0.0, stop, quality=quality)["drive"])
    assert len(out) == round(stop * 10_000)
    assert np.isfinite(out).all() and np.abs(out).max() <= 1.2 * FULL * 1.1


def test_stretch_1e3_of_a_recording_plays_it_1000_times_slower() -> None:
    project, clip, _ = one_clip(recording(0.5, high=0.0))
    project = edits.stretch_clip(project, clip, 1e3)
    # 100 s in, i.e. 0.1 s into the recording: away from its start, where a band-limited
    # resampler rings because the recording begins abruptly.
    out = Mixer().render(project, 100.0, 102.0)["drive"]
    t = 100.0 + np.arange(len(out)) / 10_000
    slow = FULL * np.sin(2 * np.pi * 50 / 1e3 * t)
    np.testing.assert_allclose(out, slow, atol=1e-6 * FULL)


@pytest.mark.parametrize("quality", list(PRESETS))
def test_one_hertz_render_of_a_48khz_recording_is_finite(quality: str) -> None:
    project, _, _ = one_clip(recording(3.0))
    out = Mixer().render(project, 0.0, 3.0, rate=1.0, quality=quality)["drive"]
    assert len(out) == 3 and np.isfinite(out).all() and np.abs(out).max() <= 1.2 * FULL


@pytest.mark.parametrize("mass", [-1.0, -1.5, -3.0])  # multiples of the rotor inertia J
def test_mass_at_and_beyond_minus_j_with_the_knob_let_go_stays_finite(mass: float) -> None:
    p = KnobParams()
    knob = KnobPhysics(p)
    knob.start(Hand("free"))
    n = 10_000
    d = np.zeros(n)
    d[:20] = 0.02
    tel = knob.run_block(
        CoefficientBlock(d, np.full(n, 0.5), np.zeros(n), np.full(n, mass * p.inertia))
    )
    assert np.isfinite(tel.angle).all() and np.isfinite(tel.torque).all()
    assert np.isfinite(tel.energy).all()
    assert np.abs(tel.torque).max() <= p.max_torque
    assert tel.flag("mass-cancels-inertia").count == n


def test_a_1hz_knob_flags_any_spring_and_stays_finite() -> None:
    p = KnobParams(rate=1.0)
    knob = KnobPhysics(p)
    knob.start(Hand("free"))
    n = 50
    tel = knob.run_block(CoefficientBlock(np.full(n, 0.01), np.full(n, 0.1), np.zeros(n)))
    assert np.isfinite(tel.angle).all() and np.isfinite(tel.energy).all()
    assert tel.flag("passivity").count == n  # K_pass = 2 * 1e-4 / 1 s = 2e-4 N*m/rad
    assert np.abs(tel.torque).max() <= p.max_torque
