"""Arbitrary bytes and arbitrary JSON into every reader: a result or FormatError, nothing else."""

from __future__ import annotations

import json
import tempfile
from pathlib import Path

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from timeline.files import importing
from timeline.plugins.file_formats import FormatError, Imported

EXTENSIONS = [".wav", ".flac", ".aiff", ".ogg", ".csv", ".txt", ".mat", ".ahap", ".haptic", ".otio"]
FUZZ = settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])

json_values = st.recursive(
    st.none() | st.booleans() | st.floats(allow_nan=False) | st.integers() | st.text(max_size=8),
    lambda inner: (
        st.lists(inner, max_size=5) | st.dictionaries(st.text(max_size=8), inner, max_size=5)
    ),
    max_leaves=30,
)
# JSON shaped like the formats, so the fuzzer gets past the first checks.
ahap_like = st.fixed_dictionaries(
    {
        "Pattern": st.lists(
            st.dictionaries(
                st.sampled_from(["Event", "ParameterCurve", "Parameter"]),
                st.dictionaries(
                    st.sampled_from(
                        [
                            "Time",
                            "EventType",
                            "EventDuration",
                            "EventParameters",
                            "ParameterID",
                            "ParameterValue",
                            "ParameterCurveControlPoints",
                        ]
                    ),
                    json_values,
                    max_size=5,
                ),
                min_size=1,
                max_size=1,
            ),
            max_size=4,
        )
    }
)
haptic_like = st.fixed_dictionaries(
    {
        "version": st.fixed_dictionaries({"major": st.sampled_from([1, 2, "1"])}),
        "signals": st.fixed_dictionaries(
            {
                "continuous": st.fixed_dictionaries(
                    {
                        "envelopes": st.dictionaries(
                            st.sampled_from(["amplitude", "frequency"]),
                            st.lists(
                                st.dictionaries(
                                    st.sampled_from(["time", "amplitude", "frequency", "emphasis"]),
                                    json_values | st.floats(0, 2),
                                    max_size=4,
                                ),
                                max_size=5,
                            ),
                        )
                    }
                )
            }
        ),
    }
)


def _read(data: bytes, ext: str) -> None:
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / f"fuzz{ext}"
        path.write_bytes(data)
        try:
            result = importing.read_file(path, rate=1000.0 if ext in (".csv", ".txt") else None)
        except FormatError as exc:
            assert str(exc) and "\n" not in str(exc)
        else:
            assert isinstance(result, Imported) and result.placements


@FUZZ
@given(st.binary(max_size=400), st.sampled_from(EXTENSIONS))
def test_arbitrary_bytes(data, ext):
    _read(data, ext)


@FUZZ
@given(
    st.binary(max_size=300),
    st.sampled_from([b"RIFF", b"fLaC", b"FORM", b"OggS", b"MATLAB 5.0 MAT-file"]),
)
def test_arbitrary_bytes_after_a_real_magic_number(data, magic):
    ext = {b"RIFF": ".wav", b"fLaC": ".flac", b"FORM": ".aiff", b"OggS": ".ogg"}.get(magic, ".mat")
    _read(magic + data, ext)


@FUZZ
@given(json_values, st.sampled_from([".ahap", ".haptic", ".otio", ".csv"]))
def test_arbitrary_json(doc, ext):
    _read(json.dumps(doc).encode(), ext)


@FUZZ
@given(ahap_like)
def test_ahap_shaped_json(doc):
    _read(json.dumps(doc).encode(), ".ahap")


@FUZZ
@given(haptic_like)
def test_haptic_shaped_json(doc):
    _read(json.dumps(doc).encode(), ".haptic")


@FUZZ
@given(
    st.lists(
        st.lists(
            st.sampled_from(["0", "1.5", "-2", "nan", "x", "", "1e400", "time"]),
            min_size=1,
            max_size=3,
        ),
        max_size=6,
    ),
    st.sampled_from([",", "\t", " ", ";"]),
)
def test_arbitrary_tables(rows, sep):
    _read("\n".join(sep.join(r) for r in rows).encode(), ".csv")
