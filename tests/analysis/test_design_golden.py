"""The analysis of a short synthetic sound, compared with the design the code made before the
analysis was sped up (tests/golden/analysis_design.json, written by
tests/golden/make/analysis_design.py): amplitude and emphasis bit for bit, frequency within 2e-8.
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
from pathlib import Path

import numpy as np
import soundfile as sf

from timeline.analysis import DEFAULTS, SoundAnalysis, analyse
from timeline.analysis.source import analyse_file
from timeline.bench.convert import META

GOLDEN = Path(__file__).resolve().parents[1] / "golden" / "analysis_design.json"
RATE = 48_000
FREQUENCY_TOLERANCE = 2e-8  # float32 spectra summed in another order may move the centroid this


def golden_sound() -> np.ndarray:
    """1.5 s of 48 kHz stereo (more than one block of the file reader): decaying bursts of three
    pitches, one slow swell, over a little noise."""
    rng = np.random.default_rng(24)
    t = np.arange(int(1.5 * RATE)) / RATE
    x = 0.01 * rng.normal(size=len(t))
    for start, hz in ((0.1, 90.0), (0.37, 400.0), (0.52, 180.0), (0.9, 2500.0), (1.31, 60.0)):
        dt = np.maximum(t - start, 0.0)
        x += (t >= start) * np.sin(2 * np.pi * hz * dt) * np.exp(-dt / 0.04)
    x += 0.3 * np.sin(2 * np.pi * 220 * t) * np.clip((t - 0.6) / 0.3, 0, 1) * (t < 1.2)
    return (0.4 * np.column_stack([x, 0.5 * x + 0.02 * rng.normal(size=len(t))])).astype(np.float32)


def _bits(values: np.ndarray) -> str:
    return hashlib.sha256(np.ascontiguousarray(values, dtype=np.float64).tobytes()).hexdigest()


def design_record(design: SoundAnalysis) -> dict[str, object]:
    """What the golden file keeps of a design: digests of the exact parts, frequency values."""
    return {
        "amplitude": _bits(design.amplitude),
        "emphasis": _bits(design.emphasis),
        "frequency_times": _bits(design.frequency[:, 0]),
        "frequency": design.frequency[:, 1].tolist(),
        "counts": [len(design.amplitude), len(design.emphasis), len(design.frequency)],
        "duration": design.duration,
    }


def golden_designs(folder: Path) -> dict[str, SoundAnalysis]:
    """The designs the golden file holds: the sound as a float WAV with the defaults and with
    Meta's analysis, and in memory (mono) normalised."""
    path = folder / "golden.wav"
    stereo = golden_sound()
    sf.write(path, stereo, RATE, subtype="FLOAT")
    normalised = dataclasses.replace(DEFAULTS, normalize=True)
    return {
        "file, defaults": analyse_file(path),
        "file, Meta's analysis": analyse_file(path, META),
        "memory, normalised": analyse(stereo[:, 0], RATE, normalised),
    }


def test_designs_are_the_ones_made_before(tmp_path: Path) -> None:
    golden = json.loads(GOLDEN.read_text())["designs"]
    found = {name: design_record(d) for name, d in golden_designs(tmp_path).items()}
    assert set(found) == set(golden)
    for name, record in found.items():
        expected = golden[name]
        assert record["counts"] == expected["counts"], name
        assert record["duration"] == expected["duration"], name
        assert record["amplitude"] == expected["amplitude"], name
        assert record["emphasis"] == expected["emphasis"], name
        assert record["frequency_times"] == expected["frequency_times"], name
        np.testing.assert_allclose(
            record["frequency"], expected["frequency"], rtol=0, atol=FREQUENCY_TOLERANCE
        )
