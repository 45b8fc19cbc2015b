"""Each perception finding just below and just above its threshold (and at it where exact)."""

from __future__ import annotations

import numpy as np
import pytest

from tests.limits.designs import KNOB, tone
from timeline import edits, generator
from timeline.limits.actuators import actuator
from timeline.limits.check import check
from timeline.limits.skin import displacement_per_unit
from timeline.limits.thresholds import AMPLITUDE_JND_DB, detection_threshold
from timeline.plugins.device_protocol import Hand


def found(report, kind: str) -> list:
    return [f for f in report.findings if f.kind == kind]


@pytest.mark.parametrize("frequency", [60.0, 250.0])
@pytest.mark.parametrize(("scale", "below"), [(0.95, True), (1.05, False)])
def test_a_knob_buzz_at_the_detection_threshold(
    frequency: float, scale: float, below: bool
) -> None:
    per_unit = displacement_per_unit(KNOB, None, np.array([frequency]))[0]
    amplitude = detection_threshold(frequency) / per_unit  # N*m peak that moves the skin enough
    report = check(tone(frequency, scale * amplitude, seconds=0.2), KNOB)
    hits = found(report, "below-detection")
    assert bool(hits) == below
    if below:
        assert hits[0].value / hits[0].limit == pytest.approx(scale, rel=0.03)


@pytest.mark.parametrize("name", ["hold", "pinch", "grasp", "grasp-turn:45", "push:20"])
@pytest.mark.parametrize(("scale", "below"), [(0.95, True), (1.05, False)])
def test_the_hand_on_the_knob_sets_the_detection_threshold(
    name: str, scale: float, below: bool
) -> None:
    hand = Hand.parse(name)
    per_unit = displacement_per_unit(KNOB, None, np.array([250.0]), hand)[0]
    amplitude = detection_threshold(250.0) / per_unit
    report = check(tone(250.0, scale * amplitude, seconds=0.2), KNOB, hand=hand)
    assert bool(found(report, "below-detection")) == below


def test_a_light_pinch_feels_what_a_heavy_grasp_does_not() -> None:
    f = np.array([250.0])
    pinch, grasp = (
        displacement_per_unit(KNOB, None, f, Hand.parse(n))[0] for n in ("pinch", "grasp")
    )
    # pinch: no finger inertia, 15 mm: 0.015 / |0.129 - 1e-5 w^2 + j w 3.9e-4| = 6.1e-4 m per N*m
    assert pinch == pytest.approx(6.09e-4, rel=0.01)
    # grasp: 0.554 kg at 20 mm adds 2.2e-4 kg*m^2: 0.020 / |0.054 - 2.3e-4 w^2 + ...| = 3.5e-5
    assert grasp == pytest.approx(3.50e-5, rel=0.01)
    buzz = tone(250.0, 2.0 * detection_threshold(250.0) / grasp * (grasp / pinch) ** 0.5)
    assert not found(check(buzz, KNOB, hand=Hand.parse("pinch")), "below-detection")
    assert found(check(buzz, KNOB, hand=Hand.parse("grasp")), "below-detection")


def test_a_hand_that_lets_go_feels_nothing_and_the_check_says_so() -> None:
    report = check(tone(250.0, 1e-9), KNOB, hand=Hand.parse("free"))
    assert not found(report, "below-detection")
    assert "the hand lets go of the knob (free): detection not checked" in report.notes


def test_the_hand_is_most_sensitive_near_250_hz() -> None:
    assert detection_threshold(250.0) == pytest.approx(1e-7)
    assert detection_threshold(125.0) == pytest.approx(1e-7 * 10 ** (12 / 20))  # -12 dB/octave
    assert detection_threshold(20.0) == detection_threshold(40.0)  # the plateau


def test_an_lra_buzz_below_detection() -> None:
    lra = actuator("lra-175")
    info = KNOB
    per_unit = displacement_per_unit(info, lra, np.array([175.0]))[0]
    amplitude = detection_threshold(175.0) / per_unit
    assert found(check(tone(175.0, 0.95 * amplitude), info, lra), "below-detection")
    assert not found(check(tone(175.0, 1.05 * amplitude), info, lra), "below-detection")


def _two_taps(gap_samples: int) -> object:
    p = edits.new_project("time")
    p, track = edits.add_track(p, "drive", "drive")
    p, tile = edits.add_tile(p, generator("constant", 0.05, "tap", value=1.0))
    p, _ = edits.add_clip(p, track, tile, 0.0, gain=0.5)
    p, _ = edits.add_clip(p, track, tile, 0.05 + gap_samples / 10_000.0, gain=0.5)
    return p


@pytest.mark.parametrize(("samples", "short"), [(99, True), (100, False), (101, False), (3, True)])
def test_gap_shorter_than_touch_resolves(samples: int, short: bool) -> None:
    hits = found(check(_two_taps(samples), KNOB), "gap-too-short")
    assert bool(hits) == short
    if short:
        # ms; the mixer may start a clip off the grid on the next sample
        assert hits[0].value == pytest.approx(samples / 10, abs=0.11)
        assert (hits[0].start, hits[0].stop) == pytest.approx(
            (0.05, 0.05 + samples / 1e4), abs=1e-4
        )


def _variants(db: float):
    p = tone(175.0, 0.05)
    p = edits.save_variant(p, "soft")
    clip = p.tracks[0].clips[0].id
    p = edits.set_clip_gain(p, clip, 10 ** (db / 20))
    return edits.save_variant(p, "loud")


@pytest.mark.parametrize(("db", "alike"), [(AMPLITUDE_JND_DB - 0.1, True),
                                           (AMPLITUDE_JND_DB + 0.1, False)])  # fmt: skip
def test_variants_closer_than_an_amplitude_jnd(db: float, alike: bool) -> None:
    hits = found(check(_variants(db), KNOB), "sub-jnd")
    assert bool(hits) == alike
    if alike:
        assert "'soft' and 'loud'" in hits[0].what
        assert hits[0].value == pytest.approx(db, abs=1e-6) and hits[0].unit == "dB"


def _clips(kind: str, ratio: float):
    p = edits.new_project("time")
    p, track = edits.add_track(p, kind, kind)
    p, tile = edits.add_tile(p, generator("constant", 0.1, "level", value=1.0))
    p, _ = edits.add_clip(p, track, tile, 0.0, gain=0.5)
    p, _ = edits.add_clip(p, track, tile, 0.3, gain=0.5 * ratio)
    return p


@pytest.mark.parametrize(("ratio", "alike"), [(1.069, True), (1.0 / 0.929, False), (1.0, False)])
def test_stiffness_clips_closer_than_a_force_jnd(ratio: float, alike: bool) -> None:
    assert bool(found(check(_clips("stiffness", ratio), KNOB), "sub-jnd")) == alike


def test_tones_closer_than_a_frequency_jnd() -> None:
    p = edits.new_project("time")
    p, track = edits.add_track(p, "drive", "drive")
    for at, f in ((0.0, 100.0), (0.3, 110.0), (0.6, 140.0)):  # 10 % apart, then 27 %
        p, tile = edits.add_tile(p, generator("sine", 0.2, f"{f:g} Hz", frequency=f))
        p, _ = edits.add_clip(p, track, tile, at, gain=0.5)
    hits = found(check(p, KNOB), "sub-jnd")
    assert len(hits) == 1 and "frequency" in hits[0].what and hits[0].start == 0.0


def test_a_crescendo_in_steps_below_a_jnd_is_one_finding() -> None:
    p = edits.new_project("time")
    p, track = edits.add_track(p, "drive", "drive")
    p, tile = edits.add_tile(p, generator("sine", 0.1, "tap", frequency=175.0))
    for i in range(5):  # +1 dB a step: 4 steps below the 2.2 dB JND, 4 dB end to end
        p, _ = edits.add_clip(p, track, tile, 0.2 * i, gain=0.3 * 10 ** (i / 20))
    p, _ = edits.add_clip(p, track, tile, 1.0, gain=0.3 * 10 ** (8 / 20))  # +4 dB: felt
    (hit,) = found(check(p, KNOB), "sub-jnd")
    assert hit.what.startswith("5 clips from") and (hit.start, hit.stop) == (0.0, 0.9)
    assert hit.value == pytest.approx(1.0, abs=0.01) and hit.unit == "dB"
