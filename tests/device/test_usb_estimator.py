"""GET_INFO 2.1 declares the firmware's velocity and acceleration estimator, and the host's
limits and flags follow the estimator the firmware runs: the same as the sim's."""

from __future__ import annotations

import struct
import zlib
from dataclasses import replace

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from device.sim import KnobParams
from device.sim.device import SimKnob
from device.usb import UsbKnob
from device.usb import protocol as p
from device.usb.emulated import EmulatedBackend, EmulatedDevice
from device.usb.firmware import EmulatedKnob
from tests.limits.designs import layered
from timeline.limits import servo
from timeline.limits.check import check
from timeline.limits.rendered import knob as rendered_knob
from timeline.plugins.device_protocol import CoefficientBlock, DeviceError, Hand

INFO = p.InfoPayload(p.KIND_KINESTHETIC, 10_000, 0.18, 100.0, 1.0, 1e-2, 1e-5, 4096, 512, 100,
                     p.ALL_CHANNELS, 50, 10, 1e-5, 1e-4, 1e-3, 1, (1, 1, 0),
                     estimator=p.ESTIMATOR_KALMAN, velocity_cutoff=2000.0,
                     observer_gains=(0.5, 2500.0, 1.25e6))  # fmt: skip


def _usb(params: KnobParams | None = None, declare: bool = True) -> UsbKnob:
    firmware = EmulatedKnob(params, declare_estimator=declare)
    return UsbKnob(backend=EmulatedBackend(EmulatedDevice(firmware)))


def _sim(estimator: str, delay: int = 1) -> SimKnob:
    return SimKnob(estimator=estimator, delay=delay)


def _mass_limit(info) -> float:  # noqa: ANN001
    """The mass limit `check` reports: the limit of the finding on a design just above it."""
    high = servo.mass_limits(info.dynamics, info.period)[1]
    report = check(layered("mass", 1.01 * high), info)
    return next(f.limit for f in report.findings if f.kind == "mass-limit")


def test_the_estimator_has_the_documented_byte_layout() -> None:
    wire = p.encode_info(INFO)
    assert len(wire) == p.INFO_SIZE == 86
    extension = struct.pack("<BBHfffff", 1, 2, 0, 2000.0, 0.0, 0.5, 2500.0, 1.25e6)
    assert wire[58:82] == extension
    assert wire[82:] == zlib.crc32(wire[:82]).to_bytes(4, "little")
    back = p.decode_info(wire)
    assert (back.protocol_minor, back.estimator) == (1, p.ESTIMATOR_KALMAN)
    assert back.observer_gains == (0.5, 2500.0, 1.25e6) and back.velocity_cutoff == 2000.0
    assert back.dynamics().estimator == "kalman"
    assert back.dynamics().observer_gains == (0.5, 2500.0, 1.25e6)


def test_a_version_2_0_answer_reads_as_not_declared() -> None:
    old = p.encode_info(replace(INFO, protocol_minor=0))
    assert len(old) == p.INFO_V20_SIZE == 58
    assert old == p.encode_info(INFO)[:58]  # 2.1 only appends: a 2.0 host reads its 58 bytes
    back = p.decode_info(old)
    assert back.estimator == p.ESTIMATOR_UNDECLARED and back.protocol_minor == 0
    assert back.dynamics().estimator == "" and not back.dynamics().estimator_declared


@pytest.mark.parametrize(
    "changes, words",
    [({"estimator": 4}, "unknown estimator 4"),
     ({"estimator": p.ESTIMATOR_FILTER}, "gains .* filter estimator"),
     ({"observer_gains": (0.0, 0.0, 0.0)}, "gains .* kalman estimator"),
     ({"observer_gains": (0.5, float("nan"), 1.0)}, "gains"),
     ({"velocity_cutoff": -1.0}, "negative or non-finite estimator cut-off"),
     ({"acceleration_cutoff": float("inf")}, "negative or non-finite estimator cut-off")],
)  # fmt: skip
def test_a_bad_estimator_is_refused_even_with_a_good_crc(changes: dict, words: str) -> None:
    with pytest.raises(p.ProtocolError, match=words):
        p.decode_info(p.encode_info(replace(INFO, **changes)))


def test_reserved_bytes_of_the_extension_are_refused() -> None:
    body = bytearray(p.encode_info(INFO)[:82])
    body[60] = 1
    with pytest.raises(p.ProtocolError, match="reserved"):
        p.decode_info(bytes(body) + zlib.crc32(body).to_bytes(4, "little"))


def test_the_emulated_knob_declares_the_kalman_gains_it_runs() -> None:
    usb = _usb()
    dyn = usb.info.dynamics
    sim = KnobParams(delay=1)
    assert (dyn.estimator, dyn.delay, dyn.velocity_cutoff) == ("kalman", 1, 2000.0)
    np.testing.assert_allclose(dyn.observer_gains, sim.observer_gains, rtol=1e-7)
    assert dyn.observer_gains == tuple(np.float32(sim.observer_gains).astype(float))
    assert usb.backend.devices[0].knob.physics.params.observer_gains.tolist() == list(
        dyn.observer_gains
    )  # the firmware runs exactly the float32 gains it declares


@pytest.mark.parametrize("estimator", ["kalman", "filter", "tracking"])
def test_the_usb_mass_limit_equals_the_sims_for_the_same_firmware(estimator: str) -> None:
    usb = _usb(KnobParams(max_torque=0.18, delay=1, estimator=estimator)).info
    assert usb.dynamics.estimator == estimator
    # the sim built with the numbers declared (float32 on the wire) gives the very same limit
    declared = usb.dynamics
    twin = SimKnob(estimator=estimator, delay=1, inertia=declared.inertia,
                   viscous=declared.damping, gains=declared.observer_gains).info  # fmt: skip
    assert _mass_limit(usb) == pytest.approx(_mass_limit(twin), rel=1e-9, abs=0)
    # and the sim's own defaults (float64) agree to 1e-9 kg*m^2 (float32 rounding, ~1e-7 rel)
    assert _mass_limit(usb) == pytest.approx(_mass_limit(_sim(estimator).info), abs=1e-9, rel=0)
    assert _mass_limit(usb) == pytest.approx(_mass_limit(_sim(estimator).info), rel=1e-6)


def test_a_filter_firmware_declares_it_and_its_limits_follow() -> None:
    filtered = _usb(KnobParams(delay=1, estimator="filter")).info.dynamics
    kalman = _usb().info.dynamics
    assert (filtered.estimator, filtered.observer_gains) == ("filter", ())
    assert (filtered.velocity_cutoff, filtered.acceleration_cutoff) == (2000.0, 200.0)
    period = 1e-4
    assert servo.mass_limits(filtered, period) == pytest.approx(
        servo.mass_limits(KnobParams(delay=1, estimator="filter").dynamics, period), rel=1e-6
    )
    # the two estimators give different mass limits: the declaration matters
    high_f, high_k = servo.mass_limits(filtered, period)[1], servo.mass_limits(kalman, period)[1]
    assert abs(high_f / high_k - 1) > 0.05


def test_streaming_flags_use_the_declared_estimator() -> None:
    """A mass just above the Kalman loop's limit is flagged on every sample while streaming."""
    usb = _usb()
    dyn, period = usb.info.dynamics, usb.info.period
    high = servo.mass_limits(dyn, period)[1]
    n = 300
    zero = np.zeros(n)
    for scale, flagged in ((0.99, 0), (1.01, n)):
        block = CoefficientBlock(zero, zero, zero, np.full(n, scale * high))
        tel = _usb().play([block], Hand("hold"))
        assert sum(f.count for f in tel.flags if f.kind == "mass-limit") == flagged


def test_a_device_that_does_not_declare_says_which_limits_it_could_not_check() -> None:
    old = _usb(declare=False).info
    assert old.dynamics.estimator == "" and old.dynamics.delay == 1
    report = check(layered("damping", 5.0), old)  # far above any estimator's damping limit
    assert [f.kind for f in report.findings] == []
    assert any("does not declare its velocity and acceleration estimator: damping and mass "
               "limits not checked" in note for note in report.notes)  # fmt: skip
    # the passivity bound does not depend on the estimator: still checked, with the delay
    kinds = [f.kind for f in check(layered("stiffness", 0.7), old).findings]
    assert kinds == ["stiffness-limit"]
    block = CoefficientBlock(np.zeros(200), np.full(200, 0.7), np.zeros(200))
    tel = _usb(declare=False).play([block], Hand("hold"))
    assert sum(f.count for f in tel.flags if f.kind == "passivity") == 200


def test_rendered_runs_the_declared_tracking_observer_not_a_kalman_one() -> None:
    usb = _usb(KnobParams(delay=1, estimator="tracking")).info
    project = layered("mass", 5e-6, seconds=0.02)
    hand = Hand("turn", 90.0)
    trace = rendered_knob(project, usb, hand)
    kalman = _usb().info.dynamics.observer_gains
    twin = replace(usb, dynamics=replace(usb.dynamics, estimator="kalman", observer_gains=kalman))
    as_kalman = rendered_knob(project, twin, hand)
    tracking = rendered_knob(project, _sim("tracking").info, hand)
    np.testing.assert_allclose(trace.rendered, tracking.rendered, rtol=0, atol=1e-6)
    assert np.abs(trace.rendered - as_kalman.rendered).max() > 1e-5


def test_the_sim_runs_gains_given_as_a_device_option() -> None:
    declared = _usb().info.dynamics.observer_gains
    text = ",".join(repr(g) for g in declared)
    assert SimKnob(delay=1, gains=text).info.dynamics.observer_gains == declared
    for bad, estimator in (("1,2", "kalman"), ("a,b,c", "kalman"), (declared, "filter")):
        with pytest.raises(DeviceError, match="observer gains are three finite numbers"):
            SimKnob(estimator=estimator, gains=bad)


@pytest.mark.parametrize("gains", [(2.5, 0.0, 0.0), (0.5, 2500.0, 1e12), (3e38, 3e38, 3e38)])
def test_an_observer_that_diverges_is_refused(gains: tuple[float, float, float]) -> None:
    with pytest.raises(p.ProtocolError, match="observer whose estimate diverges"):
        p.decode_info(p.encode_info(replace(INFO, observer_gains=gains)))


def test_the_declared_observers_converge() -> None:
    for estimator in ("kalman", "tracking"):
        dyn = _usb(KnobParams(delay=1, estimator=estimator)).info.dynamics
        assert p.observer_radius(dyn.observer_gains, 1e-4) < 0.99


@settings(max_examples=300, deadline=None)
@given(
    code=st.integers(0, 255),
    reserved=st.integers(0, 3),
    cutoffs=st.tuples(*[st.floats(width=32, allow_nan=True, allow_infinity=True)] * 2),
    gains=st.tuples(*[st.floats(width=32, allow_nan=True, allow_infinity=True)] * 3),
)
def test_any_sealed_estimator_decodes_to_a_model_or_a_protocol_error(
    code: int, reserved: int, cutoffs: tuple, gains: tuple
) -> None:
    """Fields a CRC cannot judge: whatever they hold, the host builds its loop model or refuses
    in one sentence, and a model it builds gives finite or infinite limits, never NaN."""
    body = p.encode_info(INFO)[:58] + struct.pack("<BBHfffff", 1, code, reserved, *cutoffs, *gains)
    try:
        info = p.decode_info(body + zlib.crc32(body).to_bytes(4, "little"))
    except p.ProtocolError:
        return
    dyn = info.dynamics()
    assert dyn.estimator in ("", "filter", "kalman", "tracking")
    if dyn.estimator_declared:
        assert not np.isnan(servo.damping_limit(dyn, 1e-4))


def test_rendered_on_a_device_without_a_declared_estimator_says_what_it_assumed() -> None:
    old = _usb(declare=False).info
    trace = rendered_knob(layered("mass", 5e-6, seconds=0.02), old, Hand("turn", 90.0))
    assert trace.label.endswith("(estimator not declared: the sim's Kalman observer assumed)")
    assert trace.time.size == 200
