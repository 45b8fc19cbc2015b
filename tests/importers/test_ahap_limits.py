"""The AHAP reader's bounds: files over the size cap are refused unread, and patterns over the
entry limit are refused by an exact count made without building the pattern's objects."""

from __future__ import annotations

import json
import tempfile
import tracemalloc
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from importers import _vibration as vib
from importers import ahap
from timeline.plugins.file_formats import FormatError

LIMIT = 12  # the entry limit, lowered so a property can cross it cheaply


def _escaped(key: str) -> str:
    """A JSON key written with every letter as a \\u escape (the same key once parsed)."""
    return '"' + "".join(f"\\u{ord(c):04x}" for c in key) + '"'


def _ahap_text(entries: int, escape: bool, braces: int) -> str:
    key = _escaped if escape else json.dumps
    event = (
        "{" + key("Event") + ':{"Time":%s,"EventType":"HapticTransient",'
        '"EventParameters":[{"ParameterID":"HapticIntensity","ParameterValue":0.5}]}}'
    )
    pattern = ",".join(event % round(0.01 * k, 6) for k in range(entries))
    metadata = json.dumps({"Description": "{" * braces})
    return f'{{"Version":1.0,"Metadata":{metadata},{key("Pattern")}:[{pattern}]}}'


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.integers(1, 2 * LIMIT), st.booleans(), st.integers(0, 3 * LIMIT))
def test_a_pattern_is_refused_exactly_when_it_is_over_the_limit(entries, escape, braces) -> None:
    with pytest.MonkeyPatch.context() as patch, tempfile.TemporaryDirectory() as folder:
        patch.setattr(ahap, "MAX_EVENTS", LIMIT)
        path = Path(folder) / "p.ahap"
        path.write_text(_ahap_text(entries, escape, braces))
        if entries > LIMIT:
            with pytest.raises(FormatError) as refused:
                ahap.read_design(path)
            assert str(refused.value) == (
                f"p.ahap has {entries:,} pattern entries; at most {LIMIT:,} are read"
            )
        else:
            design, _, _ = ahap.read_design(path)
            assert len(design.emphasis) == entries


def test_the_count_does_not_build_the_pattern(tmp_path, monkeypatch) -> None:
    """Over the limit, the entries are counted while each object is dropped as it is read."""
    monkeypatch.setattr(ahap, "MAX_EVENTS", 1_000)
    path = tmp_path / "many.ahap"
    path.write_text(_ahap_text(20_000, False, 0))  # 2.1 MB
    tracemalloc.start()
    try:
        with pytest.raises(FormatError, match="has 20,000 pattern entries; at most 1,000"):
            ahap.read_design(path)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert peak < 3 * path.stat().st_size  # parsed whole, it is about 8x


def test_a_file_over_the_size_cap_is_refused_before_it_is_read(tmp_path) -> None:
    path = tmp_path / "big.ahap"
    with path.open("wb") as file:
        file.truncate(vib.MAX_JSON_BYTES + 1)  # sparse: no disk is used
    tracemalloc.start()
    try:
        with pytest.raises(FormatError) as refused:
            ahap.read_design(path)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert str(refused.value) == "big.ahap is larger than 64 MB, the most an AHAP file may be"
    assert peak < 2**20


def _curve_ahap(points: int) -> str:
    controls = [{"Time": 0.001 * k, "ParameterValue": 0.5} for k in range(points)]
    return json.dumps(
        {
            "Pattern": [
                {"Event": {"Time": 0.0, "EventType": "HapticContinuous", "EventDuration": 1.0}},
                {
                    "ParameterCurve": {
                        "ParameterID": "HapticIntensityControl",
                        "Time": 0.0,
                        "ParameterCurveControlPoints": controls,
                    }
                },
            ]
        }
    )


def test_curve_points_count_against_the_entry_limit(tmp_path, monkeypatch) -> None:
    """One curve of a million points was one entry (issue 25.4): its points count too."""
    monkeypatch.setattr(ahap, "MAX_EVENTS", 100)
    path = tmp_path / "curve.ahap"
    path.write_text(_curve_ahap(98))  # 2 entries + 98 points: at the limit
    design, _, _ = ahap.read_design(path)
    assert design.amplitude_at(np.array([0.05]))[0] == pytest.approx(0.25)
    path.write_text(_curve_ahap(99))
    with pytest.raises(FormatError) as refused:
        ahap.read_design(path)
    assert str(refused.value) == (
        "curve.ahap has 2 pattern entries and 99 curve control points; at most 100 in all are read"
    )
