"""The C firmware's parser and loop under AddressSanitizer and UBSan, fed by hypothesis.

Each example is a session: START with a random mask, then random and mutated blocks (valid
ones with bits flipped, bytes replaced, cut short or lengthened, sequence numbers skipped, NaN,
inf and 1e38 samples), random vendor requests, servo periods and reports, run by the sanitized
harness (device/usb/firmware/ports/sim/fuzz_main.c), which aborts if a torque it applies is not
finite or above the maximum. The harness must exit cleanly (no sanitizer report) and every
report and GET_INFO answer it wrote must decode, with finite samples within the maximum.
Heavy: the sanitized build takes seconds and 100 sessions about 20 s (CI's heavy step).
"""

from __future__ import annotations

import struct
import subprocess

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from device.usb import protocol as p
from device.usb.firmware.build import sanitized_harness

from .conftest import count

EXAMPLES = 100
MAX_TORQUE = np.float32(0.18)

sample = st.floats(width=32, allow_nan=True, allow_infinity=True)


@st.composite
def block(draw: st.DrawFn) -> bytes:
    """A block, valid or damaged the ways a wire or a host could damage it."""
    mask = draw(st.integers(1, 15))
    n = draw(st.integers(0, 120))
    width = p.channel_count(mask)
    values = draw(st.lists(sample, min_size=n * width, max_size=n * width))
    samples = np.array(values, dtype=np.float32).reshape(n, width)
    data = bytearray(p.encode_block(p.Block(draw(st.integers(0, 6)), mask, samples,
                                            draw(st.booleans()))))  # fmt: skip
    damage = draw(st.sampled_from(["none", "flip", "byte", "cut", "extend", "junk"]))
    if damage == "flip":
        bit = draw(st.integers(0, 8 * len(data) - 1))
        data[bit // 8] ^= 1 << (bit % 8)
    elif damage == "byte":
        data[draw(st.integers(0, len(data) - 1))] = draw(st.integers(0, 255))
    elif damage == "cut":
        del data[draw(st.integers(0, len(data))) :]
    elif damage == "extend":
        data += draw(st.binary(min_size=1, max_size=40))
    elif damage == "junk":
        data = bytearray(draw(st.binary(max_size=200)))
    return bytes(data)


command = st.one_of(
    block().map(lambda b: b"\x00" + struct.pack("<H", len(b)) + b),
    st.tuples(st.integers(0, 6), st.integers(0, 0xFFFF), st.binary(max_size=12)).map(
        lambda r: struct.pack("<BBHH", 1, r[0], r[1], len(r[2])) + r[2]
    ),
    st.integers(0, 800).map(lambda n: struct.pack("<BH", 2, n)),
    st.just(b"\x03"),
    st.tuples(st.integers(0, 3), st.integers(0, 300)).map(lambda r: struct.pack("<BBH", 4, *r)),
    st.tuples(st.integers(0, 4), st.integers(0, 5), st.integers(0, 300)).map(
        lambda r: struct.pack("<BBBH", 5, *r)
    ),
)


def outputs(data: bytes) -> list[bytes]:
    """The length-prefixed answers the harness wrote."""
    found, i = [], 0
    while i < len(data):
        (n,) = struct.unpack_from("<I", data, i)
        found.append(data[i + 4 : i + 4 + n])
        i += 4 + n
    return found


@pytest.fixture(scope="module")
def harness():
    return sanitized_harness()


@pytest.mark.heavy
@settings(
    max_examples=count(EXAMPLES),
    deadline=None,
    database=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture],
)
@given(st.integers(1, 15), st.lists(command, max_size=30))
def test_random_and_mutated_blocks_never_crash_or_exceed_the_maximum(harness, mask, session):
    start = struct.pack("<BBHH", 1, p.REQ_START, mask, 0)
    done = subprocess.run(
        [str(harness)], input=start + b"".join(session) + b"\x02\xe8\x03\x03", capture_output=True,
        timeout=60, check=False,
    )  # fmt: skip
    assert done.returncode == 0 and not done.stderr, done.stderr.decode(errors="replace")[-2000:]
    kinds = [c[0] for c in session if c[0] in (3, 4, 5)] + [3]  # what each answer is
    answers = outputs(done.stdout)
    assert len(answers) == len(kinds)
    for kind, answer in zip(kinds, answers, strict=True):
        if kind == 3:
            report = p.decode_report(answer)
            assert np.isfinite(report.samples).all()
            assert (np.abs(report.samples[:, 2]) <= MAX_TORQUE).all()
        elif kind == 4 and answer:  # GET_INFO: all 86 bytes, or the first as many as asked
            assert len(answer) >= p.INFO_V20_SIZE
            whole = answer if len(answer) == p.INFO_SIZE else answer[: p.INFO_V20_SIZE]
            assert p.decode_info(whole).max_torque == MAX_TORQUE
        elif kind == 5 and len(answer) > 1:  # a descriptor, cut to the length asked for
            assert answer[1] in (1, 2, 3)
            assert len(answer) <= (32 if answer[1] == 2 else answer[0])  # configuration: 32
